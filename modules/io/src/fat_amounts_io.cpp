#include "vesalius/io/fat_amounts_io.h"

#include "vesalius/core/error.h"
#include "vesalius/io/text_file.h"

#include <nlohmann/json.hpp>

#include <limits>

namespace vesalius::io {

std::vector<std::pair<std::string, double>> readFatAmounts(const std::string& path) {
  nlohmann::json json;
  try {
    json = nlohmann::json::parse(readTextFile(path));
  } catch (const nlohmann::json::exception& e) {
    throw BadInput(path, std::string("not valid JSON: ") + e.what());
  }
  if (!json.is_object()) throw BadInput(path, "expected an object of bone names and fat amounts, e.g. {\"pelvis\": 0.4}");
  std::vector<std::pair<std::string, double>> amounts;
  for (const auto& [key, value] : json.items())
    amounts.emplace_back(key, value.is_number() ? value.get<double>() : std::numeric_limits<double>::quiet_NaN());
  return amounts;
}

}  // namespace vesalius::io
