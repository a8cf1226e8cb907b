#include "penumbra/io/scene_json_meshes.h"

#include "penumbra/io/mesh_reader.h"
#include "penumbra/io/volume_reader.h"
#include "penumbra/scene/mesh_shapes.h"

#include <array>

namespace penumbra::json_reader {
namespace {

constexpr std::array<std::pair<DetailType, const char*>, 5> kDetailNames{{{DetailType::Constant, "constant"},
                                                                           {DetailType::Noise, "noise"},
                                                                           {DetailType::Fbm, "fbm"},
                                                                           {DetailType::Ridged, "ridged"},
                                                                           {DetailType::Texture, "texture"}}};

const char* detail_name(DetailType t) {
  for (const auto& [type, name] : kDetailNames) {
    if (type == t) return name;
  }
  return "fbm";
}

vec3 scale_of(const ObjectReader& r) {
  if (!r.has("scale")) return vec3(1.0f);
  const json& s = r.at("scale");
  if (s.is_number()) return vec3(ObjectReader::to_float(s, r.key("scale")));
  return ObjectReader::to_vec3(s, r.key("scale"));
}

std::filesystem::path resolved(const std::string& file, const std::string& key, const std::filesystem::path& base_dir,
                               const SceneParseOptions& options) {
  if (file.empty()) throw InvalidScene(key, "must name a file");
  return options.resolve_file ? options.resolve_file(file, key) : resolve(base_dir, file);
}

DetailFunction read_detail(const json& j, const std::string& section, const std::filesystem::path& base_dir,
                           const SceneParseOptions& options) {
  const ObjectReader r(j, section, {"type", "frequency", "octaves", "lacunarity", "gain", "offset", "time", "value",
                                    "texture", "seed"});
  DetailFunction d;
  const std::string type = r.string("type", detail_name(d.type));
  bool known = false;
  for (const auto& [t, name] : kDetailNames) {
    if (type == name) {
      d.type = t;
      known = true;
    }
  }
  if (!known) throw InvalidScene(r.key("type"), "expected constant, noise, fbm, ridged or texture, got \"" + type + "\"");
  d.frequency = r.number("frequency", d.frequency);
  d.fractal.octaves = r.integer("octaves", d.fractal.octaves);
  d.fractal.lacunarity = r.number("lacunarity", d.fractal.lacunarity);
  d.fractal.gain = r.number("gain", d.fractal.gain);
  d.fractal.offset = r.number("offset", d.fractal.offset);
  d.time_dependent = r.has("time");
  d.fractal.time = r.number("time", 0.0f);
  d.value = r.number("value", d.value);
  const int seed = r.integer("seed", 0);
  if (seed < 0) throw InvalidScene(r.key("seed"), "must be >= 0");
  d.seed = std::uint64_t(seed);
  if (d.type == DetailType::Texture) {
    if (!r.has("texture")) throw InvalidScene(r.key("texture"), "missing: the volume file of a texture detail");
    d.texture_file = r.string("texture", "");
    const std::filesystem::path path = resolved(d.texture_file, r.key("texture"), base_dir, options);
    if (!std::filesystem::exists(path)) throw IoError(path.string(), "texture volume not found (" + r.key("texture") + ")");
    d.texture = options.load_texture ? options.load_texture(path, r.key("texture")) : read_volume(path);
  } else if (r.has("texture")) {
    throw InvalidScene(r.key("texture"), "only a detail of type \"texture\" takes a texture file");
  }
  return d;
}

MeshMaterial read_material(const json& j, const std::string& section, const std::filesystem::path& base_dir,
                           const SceneParseOptions& options) {
  const ObjectReader r(j, section, {"detail", "transfer_function", "color_detail", "color_transfer_function",
                                    "specular", "roughness", "transport_color"});
  MeshMaterial m;
  if (r.has("detail")) m.detail = read_detail(r.at("detail"), r.key("detail"), base_dir, options);
  if (r.has("transfer_function")) {
    m.tf = read_transfer_function(r.at("transfer_function"), r.key("transfer_function"), base_dir, options);
  }
  if (r.has("color_detail")) {
    m.has_color_detail = true;
    m.color_detail = read_detail(r.at("color_detail"), r.key("color_detail"), base_dir, options);
  }
  if (r.has("color_transfer_function")) {
    if (!m.has_color_detail) {
      throw InvalidScene(r.key("color_transfer_function"), "needs a color_detail whose values it colours");
    }
    m.color_tf = read_transfer_function(r.at("color_transfer_function"), r.key("color_transfer_function"), base_dir,
                                        options);
  }
  m.specular = r.number("specular", m.specular);
  m.roughness = r.number("roughness", m.roughness);
  if (r.has("transport_color")) m.transport_color = r.vector3("transport_color", vec3(0.0f));
  return m;
}

json detail_to_json(const DetailFunction& d) {
  json dj{{"type", detail_name(d.type)}, {"frequency", d.frequency},  {"octaves", d.fractal.octaves},
          {"lacunarity", d.fractal.lacunarity}, {"gain", d.fractal.gain}, {"offset", d.fractal.offset},
          {"value", d.value}, {"seed", d.seed}};
  if (d.time_dependent) dj["time"] = d.fractal.time;
  if (d.type == DetailType::Texture) dj["texture"] = d.texture_file;
  return dj;
}

}  // namespace

std::vector<MeshObject> read_meshes(const json& j, const std::filesystem::path& base_dir,
                                    const SceneParseOptions& options) {
  if (!j.is_array()) throw InvalidScene("meshes", "expected an array, got " + type_name(j));
  std::vector<MeshObject> meshes;
  for (std::size_t i = 0; i < j.size(); ++i) {
    const std::string section = fmt::format("meshes[{}]", i);
    const ObjectReader r(j[i], section,
                         {"file", "builtin", "resolution", "scale", "rotate_deg", "translate", "material"});
    MeshObject m;
    if (r.has("file") == r.has("builtin")) throw InvalidScene(section, "give exactly one of \"file\" and \"builtin\"");
    if (r.has("file")) {
      if (r.has("resolution")) throw InvalidScene(r.key("resolution"), "only builtin meshes take a resolution");
      m.source.file = r.string("file", "");
      const std::filesystem::path path = resolved(m.source.file, r.key("file"), base_dir, options);
      if (!std::filesystem::exists(path)) throw IoError(path.string(), "mesh file not found (" + r.key("file") + ")");
      m.mesh = options.load_mesh ? options.load_mesh(path, r.key("file")) : std::make_shared<TriangleMesh>(read_mesh(path));
    } else {
      m.source.builtin = r.string("builtin", "");
      m.source.resolution = r.integer("resolution", 0);
      try {
        m.mesh = make_builtin_mesh(m.source.builtin, m.source.resolution);
      } catch (const InvalidArgument& e) {
        throw InvalidScene(r.key(e.name().c_str()), e.what());
      }
    }
    m.scale = scale_of(r);
    m.rotate_deg = r.vector3("rotate_deg", m.rotate_deg);
    m.translate = r.vector3("translate", m.translate);
    if (r.has("material")) m.material = read_material(r.at("material"), r.key("material"), base_dir, options);
    meshes.push_back(std::move(m));
  }
  return meshes;
}

json meshes_to_json(const std::vector<MeshObject>& meshes) {
  json out = json::array();
  for (const MeshObject& m : meshes) {
    json mj;
    if (!m.source.builtin.empty()) {
      mj["builtin"] = m.source.builtin;
      mj["resolution"] = m.source.resolution;
    } else {
      mj["file"] = m.source.file;
    }
    mj["scale"] = to_json(m.scale);
    mj["rotate_deg"] = to_json(m.rotate_deg);
    mj["translate"] = to_json(m.translate);
    mj["material"] = {{"detail", detail_to_json(m.material.detail)},
                      {"transfer_function", to_json(m.material.tf)},
                      {"specular", m.material.specular},
                      {"roughness", m.material.roughness}};
    if (m.material.transport_color) mj["material"]["transport_color"] = to_json(*m.material.transport_color);
    if (m.material.has_color_detail) {
      mj["material"]["color_detail"] = detail_to_json(m.material.color_detail);
      mj["material"]["color_transfer_function"] = to_json(m.material.color_tf);
    }
    out.push_back(mj);
  }
  return out;
}

}  // namespace penumbra::json_reader
