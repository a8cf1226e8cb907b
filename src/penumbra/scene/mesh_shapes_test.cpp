#include "penumbra/scene/mesh_shapes.h"

#include "penumbra/base/error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

namespace penumbra {
namespace {

constexpr double kPi = std::numbers::pi;

// Every directed edge appears once and its reverse once: each undirected edge
// is in exactly two triangles that traverse it in opposite directions.
void expect_closed_and_consistent(const TriangleMesh& mesh) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  for (const glm::uvec3& t : mesh.triangles) {
    ASSERT_TRUE(t[0] != t[1] && t[1] != t[2] && t[0] != t[2]) << "degenerate triangle";
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  }
  for (const auto& [edge, count] : directed) {
    ASSERT_EQ(count, 1) << "edge " << edge.first << "->" << edge.second << " used " << count << " times";
    const auto reverse = directed.find({edge.second, edge.first});
    ASSERT_TRUE(reverse != directed.end()) << "edge " << edge.first << "->" << edge.second << " is a border";
  }
}

// Divergence theorem: sum of the tetrahedra (origin, a, b, c); positive for
// outward (counter-clockwise from outside) winding.
double signed_volume(const TriangleMesh& mesh) {
  double volume = 0.0;
  for (const glm::uvec3& t : mesh.triangles) {
    const dvec3 a(mesh.positions[t[0]]), b(mesh.positions[t[1]]), c(mesh.positions[t[2]]);
    volume += glm::dot(a, glm::cross(b, c)) / 6.0;
  }
  return volume;
}

void expect_within_unit_cube(const TriangleMesh& mesh) {
  const Box3 box = mesh.bounds();
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_GE(box.lower[axis], -1.0f - 1e-6f);
    EXPECT_LE(box.upper[axis], 1.0f + 1e-6f);
  }
}

void expect_good_mesh(const TriangleMesh& mesh) {
  EXPECT_NO_THROW(mesh.validate("builtin"));
  expect_closed_and_consistent(mesh);
  expect_within_unit_cube(mesh);
  EXPECT_GT(signed_volume(mesh), 0.0);
}

TEST(MeshShapes, EveryBuiltinIsClosedOutwardAndInsideTheUnitCube) {
  ASSERT_EQ(builtin_meshes().size(), 5u);
  for (const auto& [name, doc] : builtin_meshes()) {
    SCOPED_TRACE(name);
    EXPECT_FALSE(doc.empty());
    expect_good_mesh(*make_builtin_mesh(name, 0));
  }
  // The smallest tessellations too, where seams and wrap-around are tightest.
  const std::vector<std::pair<std::string, int>> smallest = {
      {"sphere", 1}, {"box", 3}, {"torus", 3}, {"torus-knot", 3}, {"disk", 3}};
  for (const auto& [name, resolution] : smallest) {
    SCOPED_TRACE(name);
    expect_good_mesh(*make_builtin_mesh(name, resolution));
  }
}

TEST(MeshShapes, TriangleCountsFollowTheResolution) {
  EXPECT_EQ(make_builtin_mesh("sphere", 0)->triangles.size(), 20u * 64u);  // default level 3
  EXPECT_EQ(make_builtin_mesh("sphere", 2)->triangles.size(), 20u * 16u);
  EXPECT_EQ(make_builtin_mesh("box", 0)->triangles.size(), 12u);
  EXPECT_EQ(make_builtin_mesh("box", 4)->triangles.size(), 12u * 16u);
  EXPECT_EQ(make_builtin_mesh("torus", 5)->triangles.size(), 2u * 5u * 10u);
  EXPECT_EQ(make_builtin_mesh("torus-knot", 4)->triangles.size(), 2u * 4u * 64u);
  EXPECT_EQ(make_builtin_mesh("disk", 7)->triangles.size(), 4u * 7u);
}

TEST(MeshShapes, BoxIsTheCubeOfVolumeEight) {
  for (int n : {1, 2, 5}) {
    const auto mesh = make_builtin_mesh("box", n);
    EXPECT_NEAR(signed_volume(*mesh), 8.0, 1e-5);  // float vertices on a lattice: only rounding
    const Box3 box = mesh->bounds();
    EXPECT_EQ(box.lower, vec3(-1.0f));
    EXPECT_EQ(box.upper, vec3(1.0f));
    EXPECT_EQ(mesh->positions.size(), std::size_t(6 * n * n + 2));  // shared seams, no duplicates
  }
}

TEST(MeshShapes, SphereVolumeApproachesFourThirdsPi) {
  const double exact = 4.0 / 3.0 * kPi;
  double previous_error = 0.0;
  for (int level : {2, 3, 4}) {
    const auto mesh = make_builtin_mesh("sphere", level);
    for (const vec3& p : mesh->positions) ASSERT_NEAR(glm::length(p), 1.0f, 1e-6f);
    // An inscribed convex polyhedron: never more than the ball. At level 3
    // the largest triangle's circumradius is about 0.076, so every face plane
    // is at least sqrt(1 - 0.076^2) = 0.997 from the centre and the volume
    // is at least 0.997^3 = 99.1% of the ball's.
    const double error = exact - signed_volume(*mesh);
    EXPECT_GT(error, 0.0);
    if (level == 3) {
      EXPECT_LT(error / exact, 0.01);
    }
    // The deficit goes with the squared edge length: about 4x smaller per
    // level; at least 3x leaves room for the uneven triangles.
    if (level > 2) {
      EXPECT_LT(error, previous_error / 3.0);
    }
    previous_error = error;
  }
}

TEST(MeshShapes, TorusVolumeMatchesThePolyhedralAndAnalyticValues) {
  constexpr double kMajor = 0.7, kMinor = 0.3;
  for (int n : {8, 32}) {
    const auto mesh = make_builtin_mesh("torus", n);
    for (const vec3& p : mesh->positions) {
      const double ring = std::hypot(p.x, p.y) - kMajor;
      ASSERT_NEAR(ring * ring + double(p.z) * p.z, kMinor * kMinor, 1e-6);
    }
    // The mesh is a regular n-gon of radius r swept through m = 2n flat
    // wedges; each wedge is the ruled solid {rho (1-s) e_k + rho s e_k+1}
    // whose volume is sin(2 pi / m) * (integral of rho over the n-gon), and
    // the n-gon's centroid is at rho = R. So the volume is exactly
    // m sin(2 pi/m) * R * (n/2) r^2 sin(2 pi/n): float rounding only.
    const int m = 2 * n;
    const double polyhedral = m * std::sin(2 * kPi / m) * kMajor * (n / 2.0) * kMinor * kMinor * std::sin(2 * kPi / n);
    EXPECT_NEAR(signed_volume(*mesh), polyhedral, 1e-5 * polyhedral);
    // Against 2 pi^2 R r^2: each polygon factor sin(x)/x loses at most x^2/6.
    const double analytic = 2.0 * kPi * kPi * kMajor * kMinor * kMinor;
    const double x_n = 2 * kPi / n, x_m = 2 * kPi / m;
    EXPECT_NEAR(signed_volume(*mesh), analytic, analytic * (x_n * x_n + x_m * x_m) / 6.0);
  }
}

TEST(MeshShapes, DiskIsAThinCylinder) {
  for (int n : {3, 64}) {
    const auto mesh = make_builtin_mesh("disk", n);
    // A prism over the inscribed regular n-gon: exactly (n/2) sin(2 pi/n) * 0.05.
    const double polyhedral = n / 2.0 * std::sin(2 * kPi / n) * 0.05;
    EXPECT_NEAR(signed_volume(*mesh), polyhedral, 1e-5 * polyhedral);
    const Box3 box = mesh->bounds();
    EXPECT_FLOAT_EQ(box.lower.z, -0.025f);
    EXPECT_FLOAT_EQ(box.upper.z, 0.025f);
  }
  const double x = 2 * kPi / 64, analytic = kPi * 0.05;
  EXPECT_NEAR(signed_volume(*make_builtin_mesh("disk", 0)), analytic, analytic * x * x / 6.0);
}

TEST(MeshShapes, TorusKnotVolumeIsTubeAreaTimesCurveLength) {
  // Length of the scaled (2,3) torus knot by the midpoint rule on |c'(t)|
  // (smooth and periodic, so this converges very fast).
  double length = 0.0;
  constexpr int kSteps = 20000;
  for (int i = 0; i < kSteps; ++i) {
    const double t = 2 * kPi * (i + 0.5) / kSteps;
    const double radius = 2 + std::cos(3 * t);
    const dvec3 derivative(-3 * std::sin(3 * t) * std::cos(2 * t) - 2 * radius * std::sin(2 * t),
                           -3 * std::sin(3 * t) * std::sin(2 * t) + 2 * radius * std::cos(2 * t), -3 * std::cos(3 * t));
    length += glm::length(derivative) * (2 * kPi / kSteps);
  }
  length *= 0.85 / 3.0;
  // A tube that does not intersect itself has volume (cross-section area) x
  // (length) whatever its curvature and twist. The mesh's cross-section is
  // the inscribed n-gon, (n/2) r^2 sin(2 pi/n), accounted for exactly; what
  // remains comes from cutting the curve into 16 n straight pieces with the
  // rings turned between them (chords, frame twist). That is second order in
  // the step, so the relative error must fall about 4x per doubling of n
  // (3.5x to 4.5x allowed) and is 0.53% at the default n = 16 (1% allowed).
  // A self-intersecting or mis-wound tube would break both.
  const double r = 0.15;
  std::vector<double> errors;
  for (int n : {16, 32, 64}) {
    const double expected = n / 2.0 * r * r * std::sin(2 * kPi / n) * length;
    errors.push_back(std::abs(signed_volume(*make_builtin_mesh("torus-knot", n)) / expected - 1.0));
  }
  EXPECT_LT(errors[0], 0.01);
  for (std::size_t i = 0; i + 1 < errors.size(); ++i) {
    EXPECT_GT(errors[i] / errors[i + 1], 3.5) << i;
    EXPECT_LT(errors[i] / errors[i + 1], 4.5) << i;
  }
}

TEST(MeshShapes, RejectsUnknownNamesAndBadResolutions) {
  try {
    make_builtin_mesh("teapot", 0);
    ADD_FAILURE() << "expected InvalidArgument";
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.name(), "builtin");
    EXPECT_NE(std::string(e.what()).find("teapot"), std::string::npos);
  }
  for (const auto& [name, resolution] : std::vector<std::pair<std::string, int>>{
           {"sphere", -1}, {"sphere", 9}, {"box", 513}, {"torus", 2}, {"torus-knot", 353}, {"disk", 1}}) {
    SCOPED_TRACE(name + " " + std::to_string(resolution));
    try {
      make_builtin_mesh(name, resolution);
      ADD_FAILURE() << "expected InvalidArgument";
    } catch (const InvalidArgument& e) {
      EXPECT_EQ(e.name(), "resolution");
    }
  }
}

TEST(TriangleMesh, BoundsAndValidate) {
  TriangleMesh mesh;
  const Box3 empty = mesh.bounds();
  EXPECT_GT(empty.lower.x, empty.upper.x);
  EXPECT_THROW(mesh.validate("m"), InvalidArgument);  // no triangles

  mesh.positions.push_back(vec3(0.0f, 0.0f, 0.0f));
  mesh.positions.push_back(vec3(1.0f, -2.0f, 0.0f));
  mesh.positions.push_back(vec3(0.0f, 1.0f, 3.0f));
  mesh.triangles = {glm::uvec3(0, 1, 2), glm::uvec3(0, 2, 1)};  // both sides: closed, if flat
  EXPECT_NO_THROW(mesh.validate("m"));
  EXPECT_EQ(mesh.bounds().lower, vec3(0, -2, 0));
  EXPECT_EQ(mesh.bounds().upper, vec3(1, 1, 3));

  mesh.triangles = {glm::uvec3(0, 1, 3)};
  try {
    mesh.validate("meshes[2]");
    ADD_FAILURE() << "expected InvalidArgument";
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.name(), "meshes[2]");
  }
  mesh.triangles = {glm::uvec3(0, 1, 2), glm::uvec3(0, 2, 1)};
  mesh.positions[1].y = std::nanf("");
  EXPECT_THROW(mesh.validate("m"), InvalidArgument);
}

// The inside/outside parity needs a closed, consistently wound surface: an
// open mesh or a flipped triangle is refused, while vertices split at a seam
// (equal positions, different indices) still close the surface.
TEST(TriangleMesh, ValidateRequiresAClosedConsistentlyWoundSurface) {
  TriangleMesh tet;
  tet.positions = {vec3(0.0f), vec3(1.0f, 0.0f, 0.0f), vec3(0.0f, 1.0f, 0.0f), vec3(0.0f, 0.0f, 1.0f)};
  tet.triangles = {glm::uvec3(0, 2, 1), glm::uvec3(0, 1, 3), glm::uvec3(0, 3, 2), glm::uvec3(1, 2, 3)};
  EXPECT_NO_THROW(tet.validate("m"));

  TriangleMesh open = tet;
  open.triangles.pop_back();
  EXPECT_THROW(open.validate("m"), InvalidArgument);

  TriangleMesh flipped = tet;
  flipped.triangles[3] = glm::uvec3(1, 3, 2);
  EXPECT_THROW(flipped.validate("m"), InvalidArgument);

  TriangleMesh seam = tet;  // the last face with its own copies of the vertices
  seam.positions.push_back(tet.positions[1]);
  seam.positions.push_back(tet.positions[2]);
  seam.positions.push_back(tet.positions[3]);
  seam.triangles[3] = glm::uvec3(4, 5, 6);
  EXPECT_NO_THROW(seam.validate("m"));
  seam.positions[6].z = 1.5f;  // a copy that moved: now a hole
  EXPECT_THROW(seam.validate("m"), InvalidArgument);
}

}  // namespace
}  // namespace penumbra
