// Writes docs/filtered-sat-chirp.png (the Fig. 4 experiment at a larger size)
// when PENUMBRA_FIGURE_DIR names a folder; skipped otherwise, so the suite
// stays fast. Regenerate with:
//   PENUMBRA_FIGURE_DIR=docs build/penumbra_tests --gtest_filter='ChirpFigure.*'
#include "chirp_experiment.h"
#include "penumbra/analysis/text.h"
#include "penumbra/io/image_io.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

namespace penumbra {
namespace {

using namespace penumbra::testing;

struct Plot {
  Image* image;
  int x0, y0, width, height;  // the plot area in pixels
  double x_min, x_max, y_min, y_max;

  ivec2 to_pixel(double x, double y) const {
    return ivec2(x0 + int(std::lround((x - x_min) / (x_max - x_min) * (width - 1))),
                 y0 + height - 1 - int(std::lround((y - y_min) / (y_max - y_min) * (height - 1))));
  }
  void dot(ivec2 p, vec3 color) const {
    for (int dy = 0; dy < 2; ++dy)
      for (int dx = 0; dx < 2; ++dx) {
        const int x = p.x + dx, y = p.y + dy;
        if (x >= x0 && x < x0 + width && y >= y0 && y < y0 + height) image->at(x, y) = vec4(color, 1.0f);
      }
  }
  void line(double xa, double ya, double xb, double yb, vec3 color) const {
    const ivec2 a = to_pixel(xa, ya), b = to_pixel(xb, yb);
    const int steps = std::max(1, std::max(std::abs(b.x - a.x), std::abs(b.y - a.y)));
    for (int s = 0; s <= steps; ++s) dot(a + ivec2(glm::round(vec2(b - a) * (float(s) / steps))), color);
  }
  void curve(const std::vector<double>& xs, const std::vector<double>& ys, vec3 color) const {
    for (std::size_t i = 1; i < xs.size(); ++i) line(xs[i - 1], ys[i - 1], xs[i], ys[i], color);
  }
  void tick_x(double x, const std::string& label) const {
    const ivec2 p = to_pixel(x, y_min);
    for (int d = 0; d < 5; ++d) image->at(p.x, p.y - d) = vec4(vec3(0.6f), 1.0f);
    draw_text(*image, p.x - text_width(label) / 2, y0 + height + 6, label, vec3(0.7f));
  }
  void tick_y(double y, const std::string& label) const {
    const ivec2 p = to_pixel(x_min, y);
    for (int d = 0; d < 5; ++d) image->at(p.x + d, p.y) = vec4(vec3(0.6f), 1.0f);
    draw_text(*image, x0 - text_width(label) - 4, p.y - 3, label, vec3(0.7f));
  }
  void frame(const std::string& title, const std::string& x_label, const std::string& y_label) const {
    const vec3 grey(0.45f);
    for (int x = x0; x < x0 + width; ++x) image->at(x, y0) = image->at(x, y0 + height - 1) = vec4(grey, 1.0f);
    for (int y = y0; y < y0 + height; ++y) image->at(x0, y) = image->at(x0 + width - 1, y) = vec4(grey, 1.0f);
    draw_text(*image, x0, y0 - 14, title, vec3(1.0f));
    draw_text(*image, x0 + width - text_width(x_label), y0 + height + 18, x_label, vec3(0.8f));
    draw_text(*image, x0 + 4, y0 + 4, y_label, vec3(0.8f));
  }
};

TEST(ChirpFigure, WritesTheFourierAnalysisPlot) {
  const char* dir = std::getenv("PENUMBRA_FIGURE_DIR");
  if (!dir) GTEST_SKIP() << "set PENUMBRA_FIGURE_DIR to write the figure";
  const float w = 16.0f;
  const Scene scene = chirp_scene(ivec3(256, 32, 48), 24);
  const ParameterSettings box = {{"filter_voxels", double(w)}, {"shadow_cache", false}};
  ParameterSettings gaussian = box;
  gaussian["kernel"] = std::string("gaussian");
  const Image floors[3] = {render_with(scene, "shadow-rays"), render_with(scene, "filtered-sat", box),
                           render_with(scene, "filtered-sat", gaussian)};
  const char* names[3] = {"shadow-rays (unfiltered)", "filtered-sat box, w = 16 voxels",
                          "filtered-sat gaussian, same variance"};
  const vec3 colors[3] = {vec3(0.9f), vec3(1.0f, 0.55f, 0.1f), vec3(0.3f, 0.7f, 1.0f)};

  const int n = floors[0].width();  // 255 pixels, one per voxel
  const int scale = 3;
  Image figure(n * scale + 80, 3 * (24 + 18) + 2 * 230 + 110, vec4(0.06f, 0.06f, 0.08f, 1.0f));
  draw_text(figure, 10, 6, "Chirp occluder over a floor, light from above (Ament et al. 2014, Fig. 4)", vec3(1.0f));
  int y = 26;
  for (int i = 0; i < 3; ++i) {
    draw_text(figure, 40, y, names[i], colors[i]);
    for (int py = 0; py < 24; ++py)
      for (int px = 0; px < n * scale; ++px) {
        const vec3 c = glm::clamp(vec3(floors[i].at(px / scale, py)), vec3(0.0f), vec3(1.0f));
        figure.at(40 + px, y + 12 + py) = vec4(c, 1.0f);
      }
    y += 24 + 18;
  }
  // Optical depth along the chirp axis.
  std::vector<float> tau[3];
  double tau_max = 0.0;
  for (int i = 0; i < 3; ++i) {
    tau[i] = shadow_depth_profile(floors[i]);
    for (float t : tau[i]) tau_max = std::max(tau_max, double(t));
  }
  const Plot depth{&figure, 40, y + 16, n * scale, 200, 0.0, double(n), 0.0, tau_max * 1.05};
  depth.frame("optical depth of the floor shadow along x (chirp: 1 to 32 cycles)", "x [voxels]", "tau");
  for (int x = 0; x < n; x += 64) depth.tick_x(x, std::to_string(x));
  depth.tick_y(0.0, "0");
  for (int i = 0; i < 3; ++i) {
    std::vector<double> xs, ys;
    for (int x = 0; x < n; ++x) {
      xs.push_back(x + 0.5);
      ys.push_back(tau[i][std::size_t(x)]);
    }
    depth.curve(xs, ys, colors[i]);
  }
  // Spectrum ratio against the predicted transfer functions.
  const std::vector<float> reference = windowed_spectrum(tau[0]);
  float peak = 0.0f;
  for (std::size_t k = 1; k < reference.size(); ++k) peak = std::max(peak, reference[k]);
  const Plot ratio{&figure, 40, y + 16 + 200 + 44, n * scale, 200, 0.0, 2.5, 0.0, 1.1};
  ratio.frame("|F(filtered tau)| / |F(tau)| against f w (lines: |sinc(f w)|, Gaussian of the same variance)",
              "f w  (f in cycles per voxel)", "ratio");
  const char* fw_labels[] = {"0", "0.5", "1", "1.5", "2"};
  for (int i = 0; i < 5; ++i) ratio.tick_x(0.5 * i, fw_labels[i]);
  ratio.tick_y(0.0, "0");
  ratio.tick_y(0.5, "0.5");
  ratio.tick_y(1.0, "1");
  std::vector<double> fs, sinc, gauss;
  for (int i = 0; i <= 400; ++i) {
    const double fw = 2.5 * i / 400.0;
    fs.push_back(fw);
    sinc.push_back(box_response(fw / w, w));
    gauss.push_back(gaussian_response(fw / w, w));
  }
  ratio.curve(fs, sinc, vec3(0.6f, 0.35f, 0.1f));
  ratio.curve(fs, gauss, vec3(0.15f, 0.4f, 0.6f));
  for (int i = 1; i < 3; ++i) {
    const std::vector<float> filtered = windowed_spectrum(tau[i]);
    for (std::size_t k = 1; k < reference.size(); ++k) {
      if (reference[k] < 0.2f * peak) continue;
      const ivec2 p = ratio.to_pixel(double(k) / n * w, filtered[k] / reference[k]);
      for (int d = -2; d <= 2; ++d) {
        ratio.dot(p + ivec2(d, 0), colors[i]);
        ratio.dot(p + ivec2(0, d), colors[i]);
      }
    }
  }
  const std::filesystem::path out = std::filesystem::path(dir) / "filtered-sat-chirp.png";
  write_png(out, figure);
  std::printf("wrote %s\n", out.string().c_str());
}

}  // namespace
}  // namespace penumbra
