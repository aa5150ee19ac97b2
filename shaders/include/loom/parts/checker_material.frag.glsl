// Object part "checker-material" (fragment stage): a checkerboard in world XZ alternating the
// base and the secondary colour, material.z cells per world unit, edges filtered over a pixel.
MaterialSample object_material(SurfaceInput surface) {
    vec2 cell = surface.world_position.xz * object.material.z;
    vec2 width = max(fwidth(cell), vec2(1e-4));
    // Triangle waves of period 2 per axis; their product's sign picks the colour.
    vec2 wave = clamp((abs(fract(cell * 0.5) * 2.0 - 1.0) - 0.5) / width, -0.5, 0.5);
    float mask = 0.5 - 2.0 * wave.x * wave.y;
    MaterialSample m;
    m.albedo = mix(object.base_color.rgb, object.secondary_color.rgb, mask) * surface.color.rgb;
    m.metallic = object.material.x;
    m.roughness = object.material.y;
    m.emissive = object.emissive.rgb;
    return m;
}
