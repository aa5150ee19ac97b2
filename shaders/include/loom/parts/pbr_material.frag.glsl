// Object part "pbr-material" (fragment stage): a uniform metallic-roughness material, tinted by
// the vertex colour.
MaterialSample object_material(SurfaceInput surface) {
    MaterialSample m;
    m.albedo = object.base_color.rgb * surface.color.rgb;
    m.metallic = object.material.x;
    m.roughness = object.material.y;
    m.emissive = object.emissive.rgb;
    return m;
}
