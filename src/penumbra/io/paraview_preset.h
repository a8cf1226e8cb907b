#pragma once
// ParaView colour-map presets as transfer functions.
//
// JSON (what ParaView's "Save preset" and its preset library write): an array
// of preset objects, or one object, each with "Name", "RGBPoints"
// [x, r, g, b, ...] and optionally "Points" [x, alpha, midpoint, sharpness,
// ...] for opacity. The older XML form (<ColorMap name=...><Point x= o= r= g=
// b=/>) is read when the file name ends in .xml.
//
// Conversion to penumbra's model:
// - x is normalised to [0, 1] over the RGBPoints' own range, and the TF range
//   is "data" (nullopt): a preset is a shape, applied to the volume's range.
// - Colour and opacity stops are merged: both piecewise-linear functions are
//   sampled at the union of their positions.
// - ParaView stores sRGB colours; penumbra's are linear, so each stop is
//   decoded (0.5 -> 0.214). Between stops penumbra interpolates in linear RGB,
//   not in the preset's ColorSpace (Diverging, Lab, HSV), so presets with few,
//   far-apart stops look slightly different mid-way; presets with many stops
//   (most of ParaView's library) match closely.
// - An opacity midpoint other than 0.5 is exact (an extra stop at the
//   midpoint); sharpness is ignored (treated as 0, ParaView's linear default).
// - A preset without "Points" gets a linear opacity ramp from 0 at the low end
//   to 1 at the high end, so that the volume stays visible.
// - ParaView's opacity is per unit of its "scalar opacity unit distance"; the
//   TF keeps penumbra's default unit_length (the smallest voxel spacing).
#include "penumbra/scene/transfer_function.h"

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace penumbra {

// Picks the preset called `name`, or the first one with RGBPoints when `name`
// is empty. IoError for unreadable files, malformed presets and unknown names
// (the message lists the names in the file).
TransferFunction read_paraview_preset(const std::filesystem::path& path, std::string_view name = {});

// The same from JSON text; `source` names it in errors.
TransferFunction parse_paraview_preset(std::string_view json_text, std::string_view name = {},
                                       const std::string& source = "<preset>");

// Names of the presets in a file (JSON or XML), in file order.
std::vector<std::string> paraview_preset_names(const std::filesystem::path& path);

}  // namespace penumbra
