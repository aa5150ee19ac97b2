// The per-object records of a loom::passes::RetainedScene (its retained convention): one
// ObjectRecord per submitted object, all in one storage buffer at LOOM_BINDING(0) of set 1,
// read by the vertex stage through the per-instance object index. Mirrors
// loom::passes::ObjectRecord (retained_mesh.hpp). Declared for the vertex stage only, so that
// fragment-only programs bind no record buffer.
#ifndef LOOM_PASSES_OBJECT_RECORDS_GLSL
#define LOOM_PASSES_OBJECT_RECORDS_GLSL

#ifdef LOOM_STAGE_VERTEX
struct ObjectRecord {
    mat4 model;          // object to world
    mat4 normal_matrix;  // upper 3x3: normals to world (cofactor matrix, sign-corrected)
};

layout(std430, set = LOOM_SET, binding = LOOM_BINDING(0)) readonly buffer ObjectRecords {
    ObjectRecord records[];
} object_records;
#endif

#endif
