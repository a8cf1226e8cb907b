#pragma once
// emission-absorption: unshaded direct volume rendering. The TF colour is the
// emitted radiance, L = integral T(0,t) sigma_t(t) c(t) dt + T(0,far) L_bg.
// Parameters: none. Passes: one ray-casting pass; prepare() only refreshes the
// shared macrocell grid and TF table. Lights are ignored.
#include "penumbra/render/technique.h"

namespace penumbra {

TechniqueInfo emission_absorption_info();

}  // namespace penumbra
