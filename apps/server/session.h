#pragma once
// One viewer (a browser tab): its scene, the technique instances that keep
// light-space structures between frames, and a snapshot of its scene JSON and
// volume histogram that handler threads read without waiting for a render.
//
// The methods marked "job" run on the render queue, which runs one job per
// session at a time; they are not meant to be called concurrently. The
// snapshot methods may be called from any thread at any time.
#include "penumbra/render/image.h"
#include "penumbra/render/technique.h"
#include "server/image_encoding.h"
#include "server/scene_update.h"
#include "server/session_memory.h"

#include <nlohmann/json.hpp>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace penumbra::server {

struct SessionContext {
  const DataDirectory* data = nullptr;
  VolumeCache* cache = nullptr;
  SceneLimits limits;
  SessionMemory* memory = nullptr;  // null: unaccounted (tests of one session)
};

struct FrameRequest {
  std::optional<nlohmann::json> scene;   // applied before rendering when given
  std::optional<nlohmann::json> camera;  // then this camera section (scene JSON v1) replaces the scene's
  int width = 256;
  int height = 256;
  // A cheap frame while the camera moves: the client asks for a smaller
  // image, and the ray step is multiplied by `step_scale`.
  bool preview = false;
  float step_scale = 2.0f;
  ImageFormat format = ImageFormat::Jpeg;
  int quality = 85;
};

struct Frame {
  std::vector<std::uint8_t> bytes;
  ImageFormat format = ImageFormat::Jpeg;
  int width = 0;
  int height = 0;
  std::string technique;
  float step = 0.0f;  // the ray step used, in voxels
  double prepare_ms = 0.0;
  double render_ms = 0.0;
  double encode_ms = 0.0;
  std::uint64_t samples = 0;
  std::uint64_t rebuilds = 0;  // the technique's rebuilds() after this frame
  // pathtrace (progressive in the server): the paths per pixel of the
  // estimate this frame shows, and whether it stopped growing (converged or
  // at max_total_spp); 0 and false for every other technique.
  int spp = 0;
  bool converged = false;
};

class Session {
 public:
  Session(std::string id, SessionContext context);
  ~Session();  // forgets its memory record
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  const std::string& id() const { return id_; }

  // job: replaces the scene (scene JSON v1), changing only what differs.
  void set_scene(const nlohmann::json& scene_json);
  // job: shows another volume ({"file": path} or {"builtin": name, "size":
  // [x, y, z]}) with the same TF, lights and technique: the camera frames the
  // new box, point lights keep their place relative to it, and planes and
  // clip planes (placed for the old volume) are dropped.
  void load_volume(const nlohmann::json& volume_section);
  // job: renders a frame. When the sessions' structures together exceed
  // their budget (SessionMemory), this session's are released and the frame
  // fails with OutOfMemoryBudget (HTTP 413).
  Frame render(const FrameRequest& request);
  // job: what the session's technique structures and image hold.
  std::uint64_t bytes() const;

  // Snapshots (any thread).
  bool has_scene() const;
  std::string scene_json() const;     // scene JSON v1, as last set by the client
  nlohmann::json volume_info() const; // dims, spacing, frames, range, histogram
  std::chrono::steady_clock::time_point last_used() const;
  void touch();

 private:
  void update_snapshot(bool data_changed);
  Technique& technique(const TechniqueInfo& info);

  const std::string id_;
  SessionContext context_;
  SceneState state_;
  RenderSettings client_render_;  // render settings as the client sent them
  // Technique instances, most recently used first. Switching between two
  // techniques keeps both built; older ones are dropped with their
  // light-space structures, so a session's memory stays bounded.
  static constexpr std::size_t kKeptTechniques = 2;
  std::vector<std::pair<std::string, std::unique_ptr<Technique>>> techniques_;
  Image image_;
  vec2 histogram_range_{0.0f};
  int histogram_frame_ = -1;

  mutable std::mutex snapshot_mutex_;
  std::string scene_json_;
  nlohmann::json volume_info_;
  std::atomic<std::int64_t> last_used_;
};

}  // namespace penumbra::server
