#include "server/session.h"

#include "penumbra/base/error.h"
#include "penumbra/io/scene_json.h"
#include "penumbra/techniques/pathtrace/pathtrace.h"
#include "penumbra/techniques/registry.h"
#include "server/http_error.h"
#include "server/volume_histogram.h"

#include <fmt/format.h>

#include <algorithm>

namespace penumbra::server {
namespace {

using nlohmann::json;
using Clock = std::chrono::steady_clock;

constexpr int kHistogramBins = 256;

double milliseconds(Clock::duration d) { return std::chrono::duration<double, std::milli>(d).count(); }

bool same_settings(const RenderSettings& a, const RenderSettings& b) {
  return a.width == b.width && a.height == b.height && a.step == b.step && a.technique == b.technique &&
         a.params == b.params && a.ert_threshold == b.ert_threshold && a.jitter == b.jitter;
}

std::optional<vec3> read_vec3(const json& j) {
  if (!j.is_array() || j.size() != 3) return std::nullopt;
  for (const json& c : j) {
    if (!c.is_number()) return std::nullopt;
  }
  return vec3(j[0].get<float>(), j[1].get<float>(), j[2].get<float>());
}

// Moves lights that have a position with the volume: same place relative to
// the box centre in units of the box diagonal, and intensity scaled by the
// square of the size ratio so they light the new volume as brightly.
json lights_for_new_box(json lights, const Box3& old_box, const Box3& new_box) {
  if (!lights.is_array()) return lights;
  const float old_size = std::max(glm::length(old_box.extent()), 1e-6f);
  const float ratio = glm::length(new_box.extent()) / old_size;
  for (json& light : lights) {
    if (!light.is_object() || !light.contains("position")) continue;
    const auto position = read_vec3(light["position"]);
    if (!position) continue;
    const vec3 moved = new_box.center() + (*position - old_box.center()) * ratio;
    light["position"] = json::array({moved.x, moved.y, moved.z});
    const float intensity = light.contains("intensity") && light["intensity"].is_number() ? light["intensity"].get<float>() : 1.0f;
    light["intensity"] = intensity * ratio * ratio;
    if (light.contains("radius") && light["radius"].is_number()) light["radius"] = light["radius"].get<float>() * ratio;
  }
  return lights;
}

}  // namespace

Session::Session(std::string id, SessionContext context)
    : id_(std::move(id)), context_(context), last_used_(Clock::now().time_since_epoch().count()) {}

Session::~Session() {
  if (context_.memory) context_.memory->forget(id_);
}

std::uint64_t Session::bytes() const {
  std::uint64_t sum = std::uint64_t(image_.pixel_count()) * sizeof(vec4);
  for (const auto& [name, t] : techniques_) sum += t->aux_bytes();
  return sum;
}

void Session::set_scene(const json& scene_json) {
  ClientScene next = parse_client_scene(scene_json, *context_.data, *context_.cache, context_.limits);
  const bool data_changed = state_.apply(next);
  client_render_ = next.scene.render();
  {
    const std::string text = write_scene_json(next.scene);
    std::lock_guard lock(snapshot_mutex_);
    scene_json_ = text;
  }
  update_snapshot(data_changed);
}

void Session::load_volume(const json& volume_section) {
  if (!volume_section.is_object()) throw HttpError(400, "volume", "expected {\"file\": path} or {\"builtin\": name}");
  if (state_.empty()) {
    set_scene(json{{"volume", volume_section}});
    return;
  }
  json next = state_.json();
  const Box3 old_box = state_.scene().volume().world_box();
  next["volume"] = volume_section;
  next.erase("camera");
  next.erase("planes");
  next.erase("clip_planes");
  // The new box is known only once the volume is loaded; the cache makes
  // this first parse the one that loads it and the second one free.
  const ClientScene probe = parse_client_scene(next, *context_.data, *context_.cache, context_.limits);
  if (next.contains("lights")) next["lights"] = lights_for_new_box(next["lights"], old_box, probe.scene.volume().world_box());
  set_scene(next);
}

Technique& Session::technique(const TechniqueInfo& info) {
  auto it = std::find_if(techniques_.begin(), techniques_.end(), [&](const auto& t) { return t.first == info.name; });
  if (it == techniques_.end()) {
    techniques_.insert(techniques_.begin(), {info.name, info.create()});
    if (techniques_.size() > kKeptTechniques) techniques_.resize(kKeptTechniques);
  } else {
    std::rotate(techniques_.begin(), it, it + 1);
  }
  return *techniques_.front().second;
}

Frame Session::render(const FrameRequest& request) {
  touch();
  if (request.camera) {
    if (!request.scene && state_.empty()) throw HttpError(409, "scene", "the session has no scene yet");
    nlohmann::json next = request.scene ? *request.scene : state_.json();
    next["camera"] = *request.camera;
    set_scene(next);
  } else if (request.scene) {
    set_scene(*request.scene);
  }
  if (state_.empty()) throw HttpError(409, "scene", "the session has no scene yet");
  Scene& scene = state_.scene();
  RenderSettings settings = client_render_;
  settings.width = request.width;
  settings.height = request.height;
  if (request.preview) settings.step = std::min(64.0f, settings.step * std::max(1.0f, request.step_scale));
  if (!same_settings(settings, scene.render())) scene.set_render(settings);

  const TechniqueInfo& info = find_technique(settings.technique);
  ParameterValues params(info.parameters);
  params.apply(settings.params, true, info.name);
  // A terminal progress bar (pathtrace) is for the CLI; server frames of
  // several sessions would draw over each other's.
  if (params.table().find("progress")) params.set("progress", false);
  // The viewer shows the path-traced reference converging: frames of an
  // unchanged scene add to the last one's estimate (pathtrace.h), unless
  // the client's parameters say otherwise.
  if (params.table().find("progressive") && !settings.params.count("progressive") &&
      !settings.params.count(info.name + ".progressive")) {
    params.set("progressive", true);
  }
  Technique& t = technique(info);

  Frame frame;
  const auto t0 = Clock::now();
  t.prepare(scene, params);
  if (context_.memory) {
    try {
      context_.memory->record(id_, bytes());
    } catch (const OutOfMemoryBudget&) {
      techniques_.clear();  // rebuilt by the next frame, if the others have made room by then
      image_ = Image();
      context_.memory->forget(id_);
      throw;
    }
  }
  const auto t1 = Clock::now();
  RenderStats stats;
  t.render(scene, image_, &stats);
  const auto t2 = Clock::now();
  frame.bytes = encode_image(image_, request.format, request.quality);
  const auto t3 = Clock::now();
  frame.format = request.format;
  frame.width = image_.width();
  frame.height = image_.height();
  frame.technique = info.name;
  frame.step = settings.step;
  frame.prepare_ms = milliseconds(t1 - t0);
  frame.render_ms = milliseconds(t2 - t1);
  frame.encode_ms = milliseconds(t3 - t2);
  frame.samples = stats.samples;
  frame.rebuilds = t.rebuilds();
  if (const PathTraceEstimate* e = pathtrace_estimate(t)) {
    frame.spp = e->spp;
    frame.converged = e->converged;
  }
  touch();
  return frame;
}

void Session::update_snapshot(bool data_changed) {
  const Scene& scene = state_.scene();
  const Volume& volume = scene.volume();
  const vec2 range = scene.tf_value_range();
  json info;
  {
    std::lock_guard lock(snapshot_mutex_);
    info = volume_info_;
  }
  if (data_changed || range != histogram_range_ || scene.time_step() != histogram_frame_ || info.is_null()) {
    const VolumeHistogram h = volume_histogram(volume, scene.time_step(), range, kHistogramBins);
    info["histogram"] = {{"range", {h.range.x, h.range.y}},
                         {"counts", h.counts},
                         {"below", h.below},
                         {"above", h.above},
                         {"non_finite", h.non_finite}};
    histogram_range_ = range;
    histogram_frame_ = scene.time_step();
  }
  const ValueRange values = volume.value_range();
  const VolumeSource& source = scene.volume_source();
  info["source"] = source.file.empty() ? json{{"builtin", source.builtin}} : json{{"file", source.file}};
  info["dims"] = {volume.dims().x, volume.dims().y, volume.dims().z};
  info["spacing"] = {volume.spacing().x, volume.spacing().y, volume.spacing().z};
  info["voxel_type"] = std::string(to_string(volume.type()));
  info["frames"] = volume.frame_count();
  info["time_step"] = scene.time_step();
  info["value_range"] = {values.min, values.max};
  const Box3 box = volume.world_box();
  info["box"] = {{"min", {box.lower.x, box.lower.y, box.lower.z}}, {"max", {box.upper.x, box.upper.y, box.upper.z}}};
  std::lock_guard lock(snapshot_mutex_);
  volume_info_ = std::move(info);
}

bool Session::has_scene() const {
  std::lock_guard lock(snapshot_mutex_);
  return !scene_json_.empty();
}

std::string Session::scene_json() const {
  std::lock_guard lock(snapshot_mutex_);
  return scene_json_;
}

json Session::volume_info() const {
  std::lock_guard lock(snapshot_mutex_);
  return volume_info_;
}

Clock::time_point Session::last_used() const { return Clock::time_point(Clock::duration(last_used_.load())); }

void Session::touch() { last_used_ = Clock::now().time_since_epoch().count(); }

}  // namespace penumbra::server
