#pragma once
// What the SAT techniques' tables and caches depend on, and nothing more, so
// that an edit rebuilds only what it changes (issue 22). The scene's version
// counters are coarser: the geometry version also counts floor planes, the
// lights version a light's colour and intensity, the TF version a render-only
// TF edit while a separate shadow TF is set. None of those change a table of
// extinction or a transmittance.
#include "penumbra/render/render_view.h"
#include "penumbra/scene/light.h"
#include "penumbra/scene/scene.h"

#include <cstdint>
#include <vector>

namespace penumbra {

// An extinction table's inputs: the data (and time step), the shadow TF's
// extinction as baked (its colour does not matter), and the clip planes.
struct ExtinctionInputs {
  std::uint64_t data = 0;
  std::vector<float> sigma;  // the baked shadow TF's sigma_t entries
  float value_min = 0.0f, index_scale = 0.0f;
  std::vector<vec4> clip_planes;
  bool operator==(const ExtinctionInputs&) const = default;
};

// `shadows`: the shadow view of the scene (SceneResources::shadow_view).
ExtinctionInputs extinction_inputs(const Scene& scene, const RenderView& shadows);

// Where a light's shadow comes from: its type and direction (lights at
// infinity) or position (the others); not its colour or intensity.
struct LightPlacement {
  LightType type = LightType::Directional;
  vec3 direction{0.0f};
  vec3 position{0.0f};
  bool operator==(const LightPlacement&) const = default;
};

LightPlacement light_placement(const Light& light);
std::vector<LightPlacement> light_placements(const std::vector<Light>& lights);

}  // namespace penumbra
