#include "penumbra/io/scene_json.h"

#include "penumbra/base/error.h"
#include "penumbra/io/json_reader.h"
#include "penumbra/io/paraview_preset.h"
#include "penumbra/io/scene_json_meshes.h"
#include "penumbra/io/volume_reader.h"
#include "penumbra/volume/procedural.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <initializer_list>
#include <sstream>

namespace penumbra {
namespace {

using nlohmann::json;
using json_reader::ObjectReader;
using json_reader::read_transfer_function;
using json_reader::resolve;
using json_reader::type_name;

void read_volume_section(const json& j, const std::filesystem::path& base_dir, const SceneParseOptions& options,
                         Scene& scene) {
  const ObjectReader r(j, "volume", {"file", "builtin", "size", "time_step", "spacing", "origin"});
  VolumeSource source;
  if (r.has("file") == r.has("builtin")) throw InvalidScene("volume", "give exactly one of \"file\" and \"builtin\"");
  std::filesystem::path resolved;
  if (r.has("file")) {
    if (r.has("size")) throw InvalidScene("volume.size", "only builtin volumes take a size");
    source.file = r.string("file", "");
    resolved = resolve(base_dir, source.file);
  } else {
    source.builtin = r.string("builtin", "");
    source.size = ivec3(kDefaultProceduralSize);
    if (r.has("size")) {
      const json& s = r.at("size");
      if (!s.is_array() || s.size() != 3 || !s[0].is_number_integer() || !s[1].is_number_integer() ||
          !s[2].is_number_integer()) {
        throw InvalidScene("volume.size", "expected an array of 3 integers");
      }
      for (int a = 0; a < 3; ++a) {
        const auto n = s[std::size_t(a)].get<std::int64_t>();
        if (n < 2 || n > 4096) throw InvalidScene("volume.size", fmt::format("each size must be in [2, 4096], got {}", n));
        source.size[a] = int(n);
      }
    }
  }
  if (r.has("spacing")) source.spacing = r.vector3("spacing", vec3(1.0f));
  if (r.has("origin")) source.origin = r.vector3("origin", vec3(0.0f));
  const int time_step = r.integer("time_step", 0);
  std::shared_ptr<const Volume> volume =
      options.load_volume ? options.load_volume(source, resolved) : load_scene_volume(source, resolved);
  if (!volume) throw InvalidScene("volume", "the volume could not be loaded");
  scene.set_volume(std::move(volume), time_step);
  scene.set_volume_source(std::move(source));
}

}  // namespace

TransferFunction json_reader::read_transfer_function(const json& j, const std::string& section,
                                        const std::filesystem::path& base_dir, const SceneParseOptions& options) {
  const ObjectReader r(j, section, {"points", "preset", "range", "unit_length", "density_scale"});
  TransferFunction tf;
  if (r.has("points") && r.has("preset")) throw InvalidScene(section, "give \"points\" or \"preset\", not both");
  if (r.has("preset")) {
    // A ParaView colour-map preset: {"file": "presets.json", "name": "Cool to Warm"} (name optional).
    const ObjectReader p(r.at("preset"), section + ".preset", {"file", "name"});
    if (!options.allow_preset_files) {
      throw InvalidScene(section + ".preset", "preset files are not read here; send the TF's points instead");
    }
    if (!p.has("file")) throw InvalidScene(section + ".preset.file", "missing: the preset JSON file");
    tf = read_paraview_preset(resolve(base_dir, p.string("file", "")), p.string("name", ""));
  }
  if (r.has("points")) {
    const json& pts = r.at("points");
    if (!pts.is_array() || pts.empty()) throw InvalidScene(section + ".points", "expected a non-empty array");
    std::vector<TransferFunctionPoint> points;
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const std::string key = fmt::format("{}.points[{}]", section, i);
      const json& p = pts[i];
      if (!p.is_array() || p.size() != 5) throw InvalidScene(key, "expected [value, r, g, b, alpha]");
      TransferFunctionPoint point;
      point.value = ObjectReader::to_float(p[0], key);
      point.color = vec3(ObjectReader::to_float(p[1], key), ObjectReader::to_float(p[2], key),
                         ObjectReader::to_float(p[3], key));
      point.alpha = ObjectReader::to_float(p[4], key);
      points.push_back(point);
    }
    try {
      tf = TransferFunction(std::move(points));
    } catch (const InvalidArgument& e) {
      throw InvalidScene(section + "." + e.name(), e.what());
    }
  }
  if (r.has("range")) {
    const json& range = r.at("range");
    if (range.is_string()) {
      if (range.get<std::string>() != "data") {
        throw InvalidScene(section + ".range", "expected \"data\" or [min, max]");
      }
    } else if (range.is_array() && range.size() == 2) {
      const vec2 lo_hi(ObjectReader::to_float(range[0], section + ".range"),
                       ObjectReader::to_float(range[1], section + ".range"));
      if (!(lo_hi.x < lo_hi.y)) throw InvalidScene(section + ".range", "min must be below max");
      tf.set_range(lo_hi);
    } else {
      throw InvalidScene(section + ".range", "expected \"data\" or [min, max], got " + type_name(range));
    }
  }
  if (r.has("unit_length")) {
    const float u = r.number("unit_length", 1.0f);
    if (!(u > 0.0f)) throw InvalidScene(section + ".unit_length", "must be positive");
    tf.set_unit_length(u);
  }
  const float density = r.number("density_scale", 1.0f);
  if (!(density >= 0.0f)) throw InvalidScene(section + ".density_scale", "must be >= 0");
  tf.set_density_scale(density);
  return tf;
}

namespace {

Camera read_camera(const json& j, const Box3& box) {
  const ObjectReader r(j, "camera", {"eye", "target", "up", "fov_deg", "projection", "height"});
  Camera c = Camera::framing(box);
  c.target = r.vector3("target", c.target);
  c.up = r.vector3("up", c.up);
  c.fov_deg = r.number("fov_deg", c.fov_deg);
  if (r.has("eye")) {
    c.eye = r.vector3("eye", c.eye);
  } else {
    c.eye = c.target + (Camera::framing(box).eye - box.center());
  }
  const std::string projection = r.string("projection", "perspective");
  if (projection == "perspective") {
    c.projection = Projection::Perspective;
  } else if (projection == "orthographic") {
    c.projection = Projection::Orthographic;
  } else {
    throw InvalidScene("camera.projection", fmt::format("expected \"perspective\" or \"orthographic\", got \"{}\"", projection));
  }
  c.ortho_height = r.number("height", c.ortho_height);
  return c;
}

std::vector<Light> read_lights(const json& j) {
  if (!j.is_array()) throw InvalidScene("lights", "expected an array, got " + type_name(j));
  std::vector<Light> lights;
  for (std::size_t i = 0; i < j.size(); ++i) {
    const std::string path = fmt::format("lights[{}]", i);
    const ObjectReader r(j[i], path, {"type", "direction", "position", "color", "intensity", "angle_deg", "angle_y_deg",
                                      "rotation_deg", "profile", "radius"});
    Light l;
    const std::string type = r.string("type", "directional");
    // Which keys each type takes; any other is an error naming the key.
    auto only = [&](std::initializer_list<const char*> allowed) {
      for (const char* key : {"direction", "position", "angle_deg", "angle_y_deg", "rotation_deg", "profile", "radius"}) {
        bool ok = false;
        for (const char* a : allowed) ok = ok || std::string_view(a) == key;
        if (!ok && r.has(key)) throw InvalidScene(r.key(key), fmt::format("a {} light has no {}", type, key));
      }
    };
    if (type == "directional") {
      l.type = LightType::Directional;
      only({"direction"});
    } else if (type == "point") {
      l.type = LightType::Point;
      only({"position"});
    } else if (type == "distant") {
      l.type = LightType::Distant;
      only({"direction", "angle_deg", "angle_y_deg", "rotation_deg", "profile"});
    } else if (type == "sphere") {
      l.type = LightType::Sphere;
      only({"position", "radius"});
    } else if (type == "disk") {
      l.type = LightType::Disk;
      only({"position", "direction", "radius"});
    } else if (type == "environment") {
      l.type = LightType::Environment;
      only({});
    } else {
      throw InvalidScene(path + ".type", fmt::format("expected one of directional, point, distant, sphere, disk, "
                                                     "environment; got \"{}\"", type));
    }
    if (!l.at_infinity() && !r.has("position")) throw InvalidScene(path + ".position", fmt::format("a {} light needs a position", type));
    l.direction = r.vector3("direction", l.direction);
    l.position = r.vector3("position", l.position);
    l.color = r.vector3("color", l.color);
    l.intensity = r.number("intensity", l.intensity);
    l.angle_deg = r.number("angle_deg", l.angle_deg);
    l.radius = r.number("radius", l.radius);
    const std::string profile = r.string("profile", "uniform");
    if (profile == "uniform") {
      l.profile = LightProfile::Uniform;
    } else if (profile == "gaussian") {
      l.profile = LightProfile::Gaussian;
    } else {
      throw InvalidScene(path + ".profile", fmt::format("expected \"uniform\" or \"gaussian\", got \"{}\"", profile));
    }
    // Anisotropic, rotated spreads: gaussian distant lights only (a uniform
    // cone stays isotropic). Unset angle_y_deg is the struct's -1 (isotropic).
    for (const char* key : {"angle_y_deg", "rotation_deg"}) {
      if (r.has(key) && l.profile != LightProfile::Gaussian) {
        throw InvalidScene(r.key(key), fmt::format("only a distant light with profile gaussian has {}", key));
      }
    }
    if (r.has("angle_y_deg")) {
      l.angle_y_deg = r.number("angle_y_deg", l.angle_y_deg);
      if (!(l.angle_y_deg >= 0.0f)) {
        throw InvalidScene(r.key("angle_y_deg"), fmt::format("must be in [0, 90), got {}", l.angle_y_deg));
      }
    }
    l.rotation_deg = r.number("rotation_deg", l.rotation_deg);
    lights.push_back(l);
  }
  return lights;
}

Material read_material(const json& j) {
  const ObjectReader r(j, "material",
                       {"albedo", "phase_g", "shading", "ambient", "diffuse", "specular", "shininess"});
  Material m;
  m.albedo = r.number("albedo", m.albedo);
  m.phase_g = r.number("phase_g", m.phase_g);
  const std::string shading = r.string("shading", "phase");
  if (shading == "phase") {
    m.shading = Shading::Phase;
  } else if (shading == "phong") {
    m.shading = Shading::Phong;
  } else {
    throw InvalidScene("material.shading", fmt::format("expected \"phase\" or \"phong\", got \"{}\"", shading));
  }
  m.ambient = r.number("ambient", m.ambient);
  m.diffuse = r.number("diffuse", m.diffuse);
  m.specular = r.number("specular", m.specular);
  m.shininess = r.number("shininess", m.shininess);
  return m;
}

RenderSettings read_render(const json& j) {
  const ObjectReader r(j, "render", {"width", "height", "step", "technique", "params", "ert_threshold", "jitter"});
  RenderSettings s;
  s.width = r.integer("width", s.width);
  s.height = r.integer("height", s.height);
  s.step = r.number("step", s.step);
  s.technique = r.string("technique", s.technique);
  s.ert_threshold = r.number("ert_threshold", s.ert_threshold);
  s.jitter = r.boolean("jitter", s.jitter);
  if (r.has("params")) {
    const json& p = r.at("params");
    if (!p.is_object()) throw InvalidScene("render.params", "expected an object, got " + type_name(p));
    // A value, or an object of one technique's values ("technique.name").
    const auto read_value = [&](const std::string& name, const json& v) {
      const std::string key = "render.params." + name;
      if (v.is_boolean()) {
        s.params[name] = v.get<bool>();
      } else if (v.is_number()) {
        s.params[name] = double(ObjectReader::to_float(v, key));
      } else if (v.is_string()) {
        s.params[name] = v.get<std::string>();
      } else {
        throw InvalidScene(key, "expected a number, boolean, string or an object of one technique's parameters, got " +
                                    type_name(v));
      }
    };
    for (const auto& item : p.items()) {
      if (item.key().find('.') != std::string::npos) {
        throw InvalidScene("render.params." + item.key(),
                           "write a technique's parameters as an object: {\"technique\": {\"name\": value}}");
      }
      if (!item.value().is_object()) {
        read_value(item.key(), item.value());
        continue;
      }
      for (const auto& inner : item.value().items()) {
        if (inner.value().is_object()) {
          throw InvalidScene("render.params." + item.key() + "." + inner.key(),
                             "expected a number, boolean or string, got an object");
        }
        read_value(item.key() + "." + inner.key(), inner.value());
      }
    }
  }
  return s;
}

std::vector<Plane> read_planes(const json& j) {
  if (!j.is_array()) throw InvalidScene("planes", "expected an array, got " + type_name(j));
  std::vector<Plane> planes;
  for (std::size_t i = 0; i < j.size(); ++i) {
    const ObjectReader r(j[i], fmt::format("planes[{}]", i), {"point", "normal", "color"});
    Plane p;
    p.point = r.vector3("point", p.point);
    p.normal = r.vector3("normal", p.normal);
    p.color = r.vector3("color", p.color);
    planes.push_back(p);
  }
  return planes;
}

std::vector<vec4> read_clip_planes(const json& j) {
  if (!j.is_array()) throw InvalidScene("clip_planes", "expected an array, got " + type_name(j));
  std::vector<vec4> planes;
  for (std::size_t i = 0; i < j.size(); ++i) {
    const std::string key = fmt::format("clip_planes[{}]", i);
    const json& c = j[i];
    if (!c.is_array() || c.size() != 4) throw InvalidScene(key, "expected [a, b, c, d]");
    planes.emplace_back(ObjectReader::to_float(c[0], key), ObjectReader::to_float(c[1], key),
                        ObjectReader::to_float(c[2], key), ObjectReader::to_float(c[3], key));
  }
  return planes;
}

}  // namespace

std::shared_ptr<const Volume> load_scene_volume(const VolumeSource& source, const std::filesystem::path& resolved_file) {
  std::shared_ptr<Volume> volume;
  if (!source.file.empty()) {
    if (!std::filesystem::exists(resolved_file)) {
      throw IoError(resolved_file.string(), "volume file not found (volume.file)");
    }
    volume = read_volume(resolved_file);
  } else {
    try {
      volume = make_procedural_volume(source.builtin, source.size);
    } catch (const InvalidArgument& e) {
      throw InvalidScene("volume." + e.name(), e.what());
    }
  }
  if (source.spacing) {
    try {
      volume->set_spacing(*source.spacing);
    } catch (const InvalidArgument& e) {
      throw InvalidScene("volume.spacing", e.what());
    }
    if (!source.origin) volume->center_at_origin();
  }
  if (source.origin) volume->set_origin(*source.origin);
  return volume;
}

namespace {

// The default light when a scene names none: white, directional, from the
// upper left front of the default camera.
std::vector<Light> default_lights() {
  Light l;
  l.direction = glm::normalize(vec3(0.6f, 0.8f, -1.0f));
  return {l};
}

}  // namespace

Scene parse_scene(std::string_view json_text, const std::filesystem::path& base_dir, const SceneParseOptions& options) {
  json j;
  try {
    j = json::parse(json_text);
  } catch (const json::exception& e) {
    // parse_error, and out_of_range for a number beyond a double (1e400).
    throw InvalidScene("(root)", fmt::format("not valid JSON: {}", e.what()));
  }
  const ObjectReader r(j, "", {"version", "volume", "transfer_function", "shadow_transfer_function", "camera",
                              "lights", "material", "render", "planes", "clip_planes", "background", "meshes"});
  if (r.integer("version", 1) != 1) throw InvalidScene("version", "only scene version 1 is supported");
  if (!r.has("volume")) throw InvalidScene("volume", "missing: a scene needs a volume (\"file\" or \"builtin\")");
  Scene scene;
  read_volume_section(r.at("volume"), base_dir, options, scene);
  if (r.has("transfer_function")) {
    scene.set_transfer_function(read_transfer_function(r.at("transfer_function"), "transfer_function", base_dir, options));
  }
  if (r.has("shadow_transfer_function")) {
    scene.set_shadow_transfer_function(
        read_transfer_function(r.at("shadow_transfer_function"), "shadow_transfer_function", base_dir, options));
  }
  if (r.has("meshes")) scene.set_meshes(json_reader::read_meshes(r.at("meshes"), base_dir, options));
  const Box3 box = scene.scene_box();
  scene.set_camera(read_camera(r.has("camera") ? r.at("camera") : json::object(), box));
  scene.set_lights(r.has("lights") ? read_lights(r.at("lights")) : default_lights());
  if (r.has("material")) scene.set_material(read_material(r.at("material")));
  if (r.has("render")) scene.set_render(read_render(r.at("render")));
  if (r.has("planes")) scene.set_planes(read_planes(r.at("planes")));
  if (r.has("clip_planes")) scene.set_clip_planes(read_clip_planes(r.at("clip_planes")));
  if (r.has("background")) scene.set_background(r.vector3("background", vec3(0.0f)));
  return scene;
}

Scene load_scene(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path.string(), "cannot open scene file");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_scene(text.str(), path.parent_path());
}

namespace {


// The scene holds floats; written as doubles they would print as
// 0.20000000298023224. Replace each by the double nearest to the float's
// shortest decimal form, so files read back to the same floats and look tidy.
void shorten_floats(json& j) {
  if (j.is_number_float()) {
    j = std::stod(fmt::format("{}", static_cast<float>(j.get<double>())));
  } else if (j.is_structured()) {
    for (json& child : j) shorten_floats(child);
  }
}

}  // namespace

json json_reader::to_json(const TransferFunction& tf) {
  json points = json::array();
  for (const TransferFunctionPoint& p : tf.points()) points.push_back({p.value, p.color.r, p.color.g, p.color.b, p.alpha});
  json out{{"points", points}, {"density_scale", tf.density_scale()}};
  out["range"] = tf.range() ? json::array({tf.range()->x, tf.range()->y}) : json("data");
  if (tf.unit_length()) out["unit_length"] = *tf.unit_length();
  return out;
}

using json_reader::to_json;

std::string write_scene_json(const Scene& scene) {
  json j;
  j["version"] = 1;
  const VolumeSource& src = scene.volume_source();
  json volume;
  if (!src.builtin.empty()) {
    volume["builtin"] = src.builtin;
    volume["size"] = json::array({src.size.x, src.size.y, src.size.z});
  } else {
    volume["file"] = src.file;
  }
  if (src.spacing) volume["spacing"] = to_json(*src.spacing);
  if (src.origin) volume["origin"] = to_json(*src.origin);
  volume["time_step"] = scene.time_step();
  j["volume"] = volume;

  j["transfer_function"] = to_json(scene.transfer_function());
  if (scene.shadow_transfer_function()) j["shadow_transfer_function"] = to_json(*scene.shadow_transfer_function());

  const Camera& c = scene.camera();
  j["camera"] = {{"eye", to_json(c.eye)}, {"target", to_json(c.target)}, {"up", to_json(c.up)},
                 {"fov_deg", c.fov_deg},
                 {"projection", c.projection == Projection::Perspective ? "perspective" : "orthographic"},
                 {"height", c.ortho_height}};
  json lights = json::array();
  for (const Light& l : scene.lights()) {
    json lj{{"color", to_json(l.color)}, {"intensity", l.intensity}};
    switch (l.type) {
      case LightType::Directional:
        lj["type"] = "directional";
        lj["direction"] = to_json(l.direction);
        break;
      case LightType::Point:
        lj["type"] = "point";
        lj["position"] = to_json(l.position);
        break;
      case LightType::Distant:
        lj["type"] = "distant";
        lj["direction"] = to_json(l.direction);
        lj["angle_deg"] = l.angle_deg;
        lj["profile"] = l.profile == LightProfile::Uniform ? "uniform" : "gaussian";
        if (l.angle_y_deg >= 0.0f) lj["angle_y_deg"] = l.angle_y_deg;
        if (l.rotation_deg != 0.0f) lj["rotation_deg"] = l.rotation_deg;
        break;
      case LightType::Sphere:
        lj["type"] = "sphere";
        lj["position"] = to_json(l.position);
        lj["radius"] = l.radius;
        break;
      case LightType::Disk:
        lj["type"] = "disk";
        lj["position"] = to_json(l.position);
        lj["direction"] = to_json(l.direction);
        lj["radius"] = l.radius;
        break;
      case LightType::Environment: lj["type"] = "environment"; break;
    }
    lights.push_back(lj);
  }
  j["lights"] = lights;
  const Material& m = scene.material();
  j["material"] = {{"albedo", m.albedo},     {"phase_g", m.phase_g},
                   {"shading", m.shading == Shading::Phase ? "phase" : "phong"},
                   {"ambient", m.ambient},   {"diffuse", m.diffuse},
                   {"specular", m.specular}, {"shininess", m.shininess}};
  const RenderSettings& rs = scene.render();
  json params = json::object();
  for (const auto& entry : rs.params) {
    // "technique.name" goes back into the technique's object. (Not a
    // structured binding: clang 14 cannot capture one in the lambda.)
    const std::string& key = entry.first;
    const auto dot = key.find('.');
    std::visit(
        [&](const auto& v) {
          if (dot == std::string::npos) {
            params[key] = v;
          } else {
            params[key.substr(0, dot)][key.substr(dot + 1)] = v;
          }
        },
        entry.second);
  }
  j["render"] = {{"width", rs.width},         {"height", rs.height}, {"step", rs.step},
                 {"technique", rs.technique}, {"params", params},    {"ert_threshold", rs.ert_threshold},
                 {"jitter", rs.jitter}};
  json planes = json::array();
  for (const Plane& p : scene.planes()) {
    planes.push_back({{"point", to_json(p.point)}, {"normal", to_json(p.normal)}, {"color", to_json(p.color)}});
  }
  j["planes"] = planes;
  json clips = json::array();
  for (const vec4& c4 : scene.clip_planes()) clips.push_back({c4.x, c4.y, c4.z, c4.w});
  j["clip_planes"] = clips;
  j["background"] = to_json(scene.background());
  if (!scene.meshes().empty()) j["meshes"] = json_reader::meshes_to_json(scene.meshes());
  shorten_floats(j);
  return j.dump(2);
}

}  // namespace penumbra
