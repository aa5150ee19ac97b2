#pragma once
// The one place loom::scene includes GLM, with the project's conventions (docs/architecture.md,
// "Conventions that make the two APIs agree"): clip-space depth runs 0..1 and NDC is y-up (the
// renderer gets there with clip control / a negative viewport), so projection matrices are the
// ordinary GLM ones with depth 0..1 and no y flip.
// The loom_scene target also defines these macros for everything that links it, so every
// translation unit sees GLM configured the same way.

#ifndef GLM_FORCE_DEPTH_ZERO_TO_ONE
#define GLM_FORCE_DEPTH_ZERO_TO_ONE
#endif
#ifndef GLM_FORCE_RADIANS
#define GLM_FORCE_RADIANS
#endif

#include <glm/glm.hpp>
