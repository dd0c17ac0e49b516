#include "radiosity/sources/scene_json.h"

#include "mesh/core/error.h"
#include "mesh/io/io_util.h"

#include <cctype>
#include <cmath>
#include <filesystem>

namespace dynrad::rad {

nlohmann::json scene_section(const std::string& path, const std::string& key) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".json") return nullptr;
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(detail::read_file(path));
  } catch (const nlohmann::json::exception& e) {
    throw InputError(path, 0, std::string("invalid JSON: ") + e.what());
  }
  if (!doc.is_object() || !doc.contains(key)) return nullptr;
  return doc[key];
}

double scene_number(const std::string& path, const nlohmann::json& value, const std::string& where) {
  if (!value.is_number()) throw InputError(path, 0, where + " must be a number.");
  const double x = value.get<double>();
  if (!std::isfinite(x)) throw InputError(path, 0, where + " must be finite.");
  return x;
}

}  // namespace dynrad::rad
