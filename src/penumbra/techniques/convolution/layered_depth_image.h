#pragma once
// The layered depth image (LDI) of Patel et al. 2013, section 4.1: for every
// pixel, every crossing of its centre viewing ray with the meshes' surfaces,
// front to back, with the surface normal and the mesh it belongs to. The slab
// renderer walks a pixel's list to know where the ray is inside a mesh (a
// parity test per mesh, Trapp and Doellner 2008).
//
// The paper builds it on the GPU as per-pixel linked lists and sorts them;
// here it is rasterised on the CPU the way a GPU rasterises, so that the
// parity test can trust it:
//   - vertices are projected to pixel space once, so a vertex shared by two
//     triangles lands on exactly the same point for both;
//   - a pixel centre is covered when it lies on the inner side of the three
//     edge functions, each evaluated in double with its endpoints in a fixed
//     order, so the two triangles of a shared edge get exactly opposite
//     values; a centre exactly on an edge is decided as if it were moved by
//     an infinitesimal (+eps, +eps^2) (a top-left rule), which puts it on
//     exactly one side of every edge and gives a closed mesh an even number
//     of crossings on every ray, through edges and vertices too;
//   - the depth is the exact intersection of the pixel's ray with the
//     triangle's plane (not an interpolated value);
//   - triangles are clipped against a near plane just in front of the eye, so
//     a camera inside a mesh sees the surfaces in front of it (its pixels then
//     start inside: the first crossing of that mesh is a leaving one).
// A fragment's normal is the triangle's flat (geometric) normal, or, when the
// caller gives per-corner shading normals (e.g. from smooth_corner_normals),
// their barycentric interpolation at the hit point: smooth highlights on a
// tessellated surface. Coverage, depth and `entering` never use them.
// The layout is compressed rows (CSR): offsets[pixel] .. offsets[pixel + 1]
// index the pixel's fragments. Building is parallel over bands of rows: a
// counting pass, a prefix sum, and a filling pass that also sorts each pixel.
#include "penumbra/base/math.h"
#include "penumbra/scene/camera.h"
#include "penumbra/scene/mesh.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace penumbra {

struct LdiFragment {
  float depth;           // along the camera's forward axis f: dot(hit - eye, f)
  // World-space unit normal, outward. Without shading normals: the
  // triangle's geometric normal (counter-clockwise winding). With them: the
  // shading normal, the renormalised barycentric interpolation of the
  // triangle's three corner normals at the hit point; where that is not on
  // the outer side of the triangle (dot with the geometric normal <= 0) or
  // has no length, the geometric normal instead.
  vec3 normal;
  std::uint16_t object;  // index of the mesh in the list given to build
  // The ray goes into the mesh here: dot(normal, ray direction) < 0. It is
  // taken from the triangle's winding in pixel space, the same test that
  // decided the coverage, so crossings alternate even at grazing angles.
  bool entering;
};

struct LdiPixel {
  const LdiFragment* fragments;  // front to back
  std::uint32_t count;
};

// Plain view for kernels.
struct LdiView {
  const std::uint32_t* offsets = nullptr;  // width * height + 1
  const LdiFragment* fragments = nullptr;
  int width = 0, height = 0;

  PENUMBRA_HD LdiPixel pixel(int x, int y) const {
    const std::size_t i = std::size_t(x) + std::size_t(width) * std::size_t(y);
    return LdiPixel{fragments + offsets[i], offsets[i + 1] - offsets[i]};
  }
};

class LayeredDepthImage {
 public:
  // meshes_world[i] is in world space (the caller transforms it) and gets
  // object id i. Pixel (x, y) holds the crossings of
  // camera.pixel_ray(x + 0.5, y + 0.5, width, height) at depths >= the near
  // plane (orthographic: 0; perspective: 1e-6 of the largest vertex depth). Throws InvalidArgument for a non-positive size, more than
  // 65536 meshes, a null mesh or a triangle index out of range, and
  // OutOfMemoryBudget before allocating more than the budget allows.
  // Rebuilding reuses the storage of the previous build.
  void build(const std::vector<const TriangleMesh*>& meshes_world, const CameraView& camera, int width, int height);
  // The same with shading normals: corner_normals is empty (flat normals
  // everywhere) or has one entry per mesh, null (that mesh flat) or holding
  // 3 world-space normals per triangle (corner k of triangle t at 3 t + k).
  // Throws InvalidArgument for any other size.
  void build(const std::vector<const TriangleMesh*>& meshes_world,
             const std::vector<const std::vector<vec3>*>& corner_normals, const CameraView& camera, int width,
             int height);

  LdiView view() const;
  int width() const { return width_; }
  int height() const { return height_; }
  std::size_t fragment_count() const { return fragments_.size(); }
  std::uint64_t bytes() const;  // offsets and fragments

 private:
  int width_ = 0, height_ = 0;
  std::vector<std::uint32_t> offsets_;
  std::vector<LdiFragment> fragments_;
};

// Smooth shading normals of a mesh, 3 per triangle (corner k of triangle t at
// 3 t + k), for LayeredDepthImage::build. A corner's normal is the
// area-weighted average of the geometric normals of the triangles around its
// vertex whose normals are within `crease_deg` of its own triangle's: a
// curved tessellated surface gets smooth normals, a sharp edge (a box's 90
// degrees with the default 60) stays sharp, so a flat face keeps its exact
// face normal. Vertices at exactly equal positions are one vertex (welded,
// as TriangleMesh::validate's closedness test does), so seams where a file
// splits vertices do not show. A triangle without area gets zero normals
// (the LDI then uses its geometric normal). Indices must be in range.
std::vector<vec3> smooth_corner_normals(const TriangleMesh& mesh, float crease_deg = 60.0f);

}  // namespace penumbra
