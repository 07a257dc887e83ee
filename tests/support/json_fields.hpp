#pragma once
/// Numbers out of the one-line JSON summaries the programs print (--json), for tests.
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

namespace hapticctrl::test {

/// Numbers of `"key":[...]` (or `"key":n`) in a flat JSON object; empty when the key is absent.
inline std::vector<double> json_numbers(const std::string& json, const std::string& key) {
  const auto at = json.find("\"" + key + "\":");
  if (at == std::string::npos) {
    return {};
  }
  std::string text = json.substr(at + key.size() + 3);
  text = text[0] == '[' ? text.substr(1, text.find(']') - 1)
                        : text.substr(0, text.find_first_of(",}"));
  std::vector<double> values;
  std::istringstream in(text);
  for (std::string v; std::getline(in, v, ',');) {
    values.push_back(std::stod(v));
  }
  return values;
}

/// The number of `"key":n` (the first of an array); NaN when the key is absent.
inline double json_number(const std::string& json, const std::string& key) {
  const std::vector<double> values = json_numbers(json, key);
  return values.empty() ? std::nan("") : values.front();
}

}  // namespace hapticctrl::test
