#pragma once
// DetailView: the plain struct kernels evaluate a mesh's volumetric detail
// function (mesh.h, DetailFunction) through, at object-space positions:
//   Constant  `value` everywhere;
//   Noise     improved noise of frequency * p (4D with fractal.time as w when
//             time dependent), likewise
//   Fbm       fbm and
//   Ridged    the ridged multifractal (volumetric_detail.h);
//   Texture   the texture volume stretched over the mesh's object-space
//             bounds: the bounds' corners land on the corner voxel centres
//             (index = (p - lower) / extent * (dims - 1)), trilinear and
//             clamped outside; an axis where the bounds are flat reads index 0.
// DetailResources owns what the view points at (the permutation table, the
// texture volume); it lives apart from mesh.h because mesh.h includes
// volumetric_detail.h.
#include "penumbra/base/math.h"
#include "penumbra/base/ray.h"
#include "penumbra/scene/mesh.h"
#include "penumbra/scene/volumetric_detail.h"
#include "penumbra/volume/volume_view.h"

#include <memory>

namespace penumbra {

struct DetailView {
  DetailType type = DetailType::Constant;
  float frequency = 1.0f;
  FractalParams fractal;
  bool time_dependent = false;
  float value = 0.0f;
  const NoiseTable* noise = nullptr;  // noise types
  VolumeView texture;                 // Texture (data == nullptr: no texture, reads 0)
  Box3 bounds;                        // Texture: the mesh's object-space bounds

  PENUMBRA_HD float operator()(vec3 object_position) const {
    switch (type) {
      case DetailType::Constant: return value;
      case DetailType::Noise: {
        const vec3 p = object_position * frequency;
        return time_dependent ? improved_noise(*noise, vec4(p, fractal.time)) : improved_noise(*noise, p);
      }
      case DetailType::Fbm: {
        const vec3 p = object_position * frequency;
        return time_dependent ? fbm(*noise, vec4(p, fractal.time), fractal) : fbm(*noise, p, fractal);
      }
      case DetailType::Ridged: {
        const vec3 p = object_position * frequency;
        return time_dependent ? ridged_multifractal(*noise, vec4(p, fractal.time), fractal)
                              : ridged_multifractal(*noise, p, fractal);
      }
      case DetailType::Texture: {
        if (texture.data == nullptr) return 0.0f;
        const vec3 extent = bounds.extent();
        const vec3 last = vec3(texture.dims - 1);
        vec3 index(0.0f);
        for (int axis = 0; axis < 3; ++axis)
          if (extent[axis] > 0.0f)
            index[axis] = (object_position[axis] - bounds.lower[axis]) / extent[axis] * last[axis];
        return texture.sample_index(index);
      }
    }
    return value;
  }
};

class DetailResources {
 public:
  DetailResources() = default;
  // `bounds`: the mesh's object-space bounds (TriangleMesh::bounds()).
  // Throws InvalidArgument("detail.texture") for a Texture detail whose
  // volume is not loaded, InvalidArgument("detail.frequency") for a frequency
  // that is not finite, InvalidArgument("detail.octaves") for octaves
  // outside [0, 32] and InvalidArgument("detail.lacunarity") for a lacunarity
  // that is not finite.
  DetailResources(const DetailFunction& detail, const Box3& bounds);

  // Valid while this object lives (it may be moved: the view is made anew).
  DetailView view() const;

 private:
  DetailView view_;  // without the pointers
  NoiseTable noise_;
  std::shared_ptr<const Volume> texture_;
};

}  // namespace penumbra
