#include "penumbra/scene/material.h"

#include "penumbra/base/error.h"

#include <fmt/format.h>

namespace penumbra {

void Material::validate() const {
  auto non_negative = [](const char* key, float v) {
    if (!(v >= 0.0f && is_finite(v))) throw InvalidScene(key, fmt::format("must be a finite number >= 0, got {}", v));
  };
  non_negative("material.albedo", albedo);
  non_negative("material.ambient", ambient);
  non_negative("material.diffuse", diffuse);
  non_negative("material.specular", specular);
  non_negative("material.shininess", shininess);
  if (albedo > 1.0f) throw InvalidScene("material.albedo", fmt::format("must be in [0, 1], got {}", albedo));
  if (!(phase_g > -1.0f && phase_g < 1.0f)) {
    throw InvalidScene("material.phase_g", fmt::format("must be in (-1, 1), got {}", phase_g));
  }
}

}  // namespace penumbra
