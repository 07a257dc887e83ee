// Implements type_hash.hpp from the table type_hashes.py generates.
#include "hapticctrl/ros2types/type_hash.hpp"

#include "ros2_type_hashes.hpp"

namespace hapticctrl::ros2types {

std::string_view type_hash(std::string_view dds_type) noexcept {
  for (const generated::TypeHash& t : generated::kTypeHashes) {
    if (t.dds_type == dds_type) {
      return t.rihs01;
    }
  }
  return {};
}

std::string type_hash_user_data(std::string_view dds_type) {
  const std::string_view hash = type_hash(dds_type);
  return hash.empty() ? std::string() : "typehash=" + std::string(hash) + ";";
}

}  // namespace hapticctrl::ros2types
