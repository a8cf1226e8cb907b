#pragma once
// phong: gradient Blinn-Phong shading of every sample, any number of lights,
// no shadows: albedo * c * (ambient + sum kd max(0, n.l) L) + sum ks (n.h)^s L,
// with n the normalised central-difference gradient facing the viewer and the
// material's ambient / diffuse / specular / shininess (scene "material").
// Parameters: none. Passes: one ray-casting pass.
#include "penumbra/render/technique.h"

namespace penumbra {

TechniqueInfo phong_info();

}  // namespace penumbra
