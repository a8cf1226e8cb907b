#include "penumbra/base/error.h"
#include "penumbra/render/parameters.h"

#include <gtest/gtest.h>

namespace penumbra {
namespace {

ParameterTable table() {
  return ParameterTable{{
      ParameterSpec::real("filter_voxels", 9.0, 1.0, 64.0, "filter width"),
      ParameterSpec::integer("nodes", 3, 1, 16, "deep shadow map nodes"),
      ParameterSpec::flag("cache", false, "use a cache"),
      ParameterSpec::choice("kernel", "box", {"box", "gaussian"}, "filter"),
  }};
}

TEST(Parameters, DefaultsAndTypedAccess) {
  const ParameterValues v(table());
  EXPECT_EQ(v.number("filter_voxels"), 9.0);
  EXPECT_EQ(v.integer("nodes"), 3);
  EXPECT_FALSE(v.flag("cache"));
  EXPECT_EQ(v.choice("kernel"), "box");
}

TEST(Parameters, ParsesAndValidatesCommandLineText) {
  ParameterValues v(table());
  v.set("filter_voxels", table().at("filter_voxels").parse("15.5"));
  v.set("nodes", table().at("nodes").parse("8"));
  v.set("cache", table().at("cache").parse("on"));
  v.set("kernel", table().at("kernel").parse("gaussian"));
  EXPECT_EQ(v.number("filter_voxels"), 15.5);
  EXPECT_EQ(v.integer("nodes"), 8);
  EXPECT_TRUE(v.flag("cache"));
  EXPECT_EQ(v.choice("kernel"), "gaussian");
  EXPECT_THROW(table().at("filter_voxels").parse("abc"), InvalidArgument);
  EXPECT_THROW(table().at("filter_voxels").parse("100"), InvalidArgument);
  EXPECT_THROW(table().at("nodes").parse("2.5"), InvalidArgument);
  EXPECT_THROW(table().at("cache").parse("maybe"), InvalidArgument);
  EXPECT_THROW(table().at("kernel").parse("tent"), InvalidArgument);
}

TEST(Parameters, UnknownNamesAreErrorsThatNameTheParameter) {
  ParameterValues v(table());
  try {
    v.set("filter_voxel", 3.0);
    FAIL() << "expected InvalidArgument";
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.name(), "filter_voxel");
    EXPECT_NE(std::string(e.what()).find("filter_voxels"), std::string::npos);  // lists the known names
  }
  EXPECT_THROW(v.number("nope"), InvalidArgument);
  // Lenient application skips names the table does not declare.
  EXPECT_NO_THROW(v.apply({{"other_technique_param", 1.0}, {"nodes", 4.0}}, false));
  EXPECT_EQ(v.integer("nodes"), 4);
  EXPECT_THROW(v.apply({{"other_technique_param", 1.0}}, true), InvalidArgument);
}

// Scene JSON's per-technique objects arrive as "technique.name" keys; a flat
// name another technique shares with different values (pathtrace's and
// occlusion-map's "mode") is skipped by the one that refuses it unless it is
// the scene's own technique.
TEST(Parameters, PerTechniqueKeysAndSharedFlatNames) {
  ParameterSettings settings;
  settings["kernel"] = std::string("tent");        // another technique's choice of the same name
  settings["shadow-map.nodes"] = 12.0;            // another technique's
  settings["filtered-sat.filter_voxels"] = 4.0;  // this one's
  settings["cache"] = true;
  ParameterValues v(table());
  v.apply(settings, false, "filtered-sat");
  EXPECT_EQ(v.choice("kernel"), "box");
  EXPECT_EQ(v.integer("nodes"), 3);
  EXPECT_EQ(v.number("filter_voxels"), 4.0);
  EXPECT_TRUE(v.flag("cache"));
  // As the scene's own technique, a refused value is an error naming it.
  try {
    ParameterValues(table()).apply(settings, true, "filtered-sat");
    FAIL() << "'tent' was accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.name(), "kernel");
  }
  // A per-technique key is strict: an undeclared name is an error.
  ParameterSettings typo;
  typo["filtered-sat.filter_voxel"] = 4.0;
  EXPECT_THROW(ParameterValues(table()).apply(typo, false, "filtered-sat"), InvalidArgument);
  EXPECT_NO_THROW(ParameterValues(table()).apply(typo, false, "cssm"));
}

TEST(Parameters, RejectsWrongTypesFromScenes) {
  ParameterValues v(table());
  EXPECT_THROW(v.set("filter_voxels", std::string("wide")), InvalidArgument);
  EXPECT_THROW(v.set("cache", 1.0), InvalidArgument);
  EXPECT_THROW(v.set("kernel", true), InvalidArgument);
}

}  // namespace
}  // namespace penumbra
