// The mesh BVH against brute force: every crossing of random rays with the
// built-in shapes, and the parity that says whether a point is inside.
#include "penumbra/scene/mesh_bvh.h"

#include "penumbra/base/rng.h"
#include "penumbra/scene/mesh_shapes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

namespace penumbra {
namespace {

std::vector<float> brute_force(const TriangleMesh& mesh, const Ray& ray) {
  std::vector<float> ts;
  for (const glm::uvec3& t : mesh.triangles) {
    const vec3 a = mesh.positions[t.x];
    const float hit = MeshBvhView::crossing(BvhTriangle{a, mesh.positions[t.y] - a, mesh.positions[t.z] - a}, ray);
    if (hit > 0.0f) ts.push_back(hit);
  }
  std::sort(ts.begin(), ts.end());
  return ts;
}

vec3 random_direction(Pcg32& rng) {
  const float z = 2.0f * rng.next_float() - 1.0f, phi = 6.2831853f * rng.next_float();
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  return vec3(r * std::cos(phi), r * std::sin(phi), z);
}

TEST(MeshBvh, FindsEveryCrossingBruteForceFinds) {
  for (const char* shape : {"sphere", "torus", "torus-knot", "box"}) {
    const TriangleMesh mesh = *make_builtin_mesh(shape, 0);
    const MeshBvh bvh(mesh);
    EXPECT_LT(bvh.depth(), kBvhStackDepth - 1) << shape;
    Pcg32 rng(7);
    int with_hits = 0;
    for (int i = 0; i < 300; ++i) {
      // From anywhere around the shape, half of the rays aimed at its middle.
      const vec3 origin = (vec3(rng.next_float(), rng.next_float(), rng.next_float()) * 2.0f - 1.0f) * 1.5f;
      const vec3 aim = (vec3(rng.next_float(), rng.next_float(), rng.next_float()) - 0.5f) * 0.6f;
      const Ray ray{origin, i % 2 == 0 ? random_direction(rng) : glm::normalize(aim - origin)};
      const std::vector<float> expected = brute_force(mesh, ray);
      float hits[64];
      const int n = bvh.view().crossings(ray, 0.0f, kInfinity, hits, 64);
      ASSERT_EQ(n, int(expected.size())) << shape << " ray " << i;
      std::sort(hits, hits + n);
      for (int k = 0; k < n; ++k) EXPECT_FLOAT_EQ(hits[k], expected[std::size_t(k)]) << shape << " ray " << i;
      with_hits += n > 0;
      // A window of the ray keeps only the crossings inside it.
      if (n >= 2) {
        const float lo = 0.5f * (hits[0] + hits[1]);
        EXPECT_EQ(bvh.view().crossings(ray, lo, kInfinity, hits, 64), n - 1) << shape;
      }
    }
    EXPECT_GT(with_hits, 100) << shape;
  }
}

// Odd crossings toward infinity: inside. Points on a grid against the
// sphere's analytic inside (the tessellation's radial error is below 1 %).
TEST(MeshBvh, ParityTellsInsideFromOutside) {
  const TriangleMesh mesh = *make_builtin_mesh("sphere", 4);
  const MeshBvh bvh(mesh);
  Pcg32 rng(3);
  int checked = 0;
  for (int i = 0; i < 2000; ++i) {
    const vec3 p = vec3(rng.next_float(), rng.next_float(), rng.next_float()) * 2.4f - 1.2f;
    const float r = glm::length(p);
    if (std::abs(r - 1.0f) < 0.01f) continue;
    float hits[64];
    const int n = bvh.view().crossings(Ray{p, random_direction(rng)}, 0.0f, kInfinity, hits, 64);
    EXPECT_EQ(n % 2 == 1, r < 1.0f) << "point at radius " << r;
    ++checked;
  }
  EXPECT_GT(checked, 1900);
}

TEST(MeshBvh, EmptyMeshHasNoCrossings) {
  const MeshBvh bvh{TriangleMesh{}};
  float hits[4];
  EXPECT_EQ(bvh.view().crossings(Ray{vec3(0.0f), vec3(1.0f, 0.0f, 0.0f)}, 0.0f, kInfinity, hits, 4), 0);
}

}  // namespace
}  // namespace penumbra
