// Pass part "masked-shadow-caster" (fragment stage): depth only, but the object's material runs
// first, so that what its alpha mode discards (glTF MASK below the cutoff) casts no shadow. The
// pass pairs it with the "camera" part looking from the light, which places the vertex and
// interpolates the surface the material needs.
void main() {
    SurfaceInput s = surface_input();
    object_material(s);
}
