#pragma once
// The scene's closed meshes as media for the path tracer (issue 23): inside
// mesh m the extinction and colour are its material TF at its detail
// function (render/mesh_media.h, the medium every technique that draws
// meshes samples). Each mesh is one more medium added to the volume's, and a
// sum of media can be tracked one medium at a time: the first real collision of the sum is the nearest
// of the media's own first collisions (independent Poisson processes of
// rates sigma_i add up to one of rate sum sigma_i, and the collision belongs
// to medium i with probability sigma_i / sum), and the transmittance of the
// sum is the product of theirs. So the volume's delta and ratio tracking
// stay as they are (free_flight.h) and each mesh adds its own, against the
// majorant sigma_max of its TF over the parts of the ray inside it (the
// BVH's crossings, sorted; an odd number of crossings from a point to
// infinity puts the point inside).
#include "penumbra/base/rng.h"
#include "penumbra/render/mesh_media.h"
#include "penumbra/techniques/pathtrace/free_flight.h"

#include <cstdint>

namespace penumbra {

// Delta tracking through every mesh over [0, t_max]: true and the nearest
// real collision in `hit` (which keeps the caller's if none is nearer).
PENUMBRA_HD inline bool mesh_delta_tracking(const MeshesView& meshes, const Ray& ray, float t_max, Pcg32& rng,
                                            Collision& hit, std::uint64_t& lookups) {
  bool collided = false;
  for (int m = 0; m < meshes.count; ++m) {
    const MeshMaterialView& mat = meshes.objects[m];
    const float majorant = mat.sigma_max;
    if (!(majorant > 0.0f)) continue;
    const float limit = collided ? hit.t : t_max;
    for_each_inside_part(meshes, m, ray, limit, [&](float a, float b) {
      for (float t = a;;) {
        t += exponential_step(rng, majorant);
        if (t >= b) return true;
        ++lookups;
        const vec4 medium = mat.medium(ray.at(t));
        if (rng.next_float() * majorant < medium.a) {
          hit = Collision{t, vec3(medium), medium.a};
          collided = true;
          return false;
        }
      }
    });
  }
  return collided;
}

// Ratio-tracking estimate of the meshes' transmittance of light along
// [0, t_max], per channel: each mesh's extinction times its light_weight (1
// - its transport colour) against its grey majorant, which bounds every
// channel (light_weight <= 1). The roulette acts on the largest channel and
// keeps the others' ratio to it; for grey media all three are the scalar
// estimate (the same random numbers as one channel).
PENUMBRA_HD inline vec3 mesh_ratio_tracking(const MeshesView& meshes, const Ray& ray, float t_max, Pcg32& rng,
                                            std::uint64_t& lookups) {
  vec3 transmittance(1.0f);
  for (int m = 0; m < meshes.count && max_component(transmittance) > 0.0f; ++m) {
    const MeshMaterialView& mat = meshes.objects[m];
    const float majorant = mat.sigma_max;
    if (!(majorant > 0.0f)) continue;
    for_each_inside_part(meshes, m, ray, t_max, [&](float a, float b) {
      for (float t = a;;) {
        t += exponential_step(rng, majorant);
        if (t >= b) return true;
        ++lookups;
        const float sigma = mat.medium(ray.at(t)).a;
        transmittance *= glm::max(vec3(0.0f), 1.0f - (sigma / majorant) * mat.light_weight);
        const float largest = max_component(transmittance);
        if (largest < kRatioRouletteThreshold) {
          if (rng.next_float() * kRatioRouletteThreshold >= largest) {
            transmittance = vec3(0.0f);
            return false;
          }
          transmittance *= kRatioRouletteThreshold / largest;
        }
      }
    });
  }
  return transmittance;
}

}  // namespace penumbra
