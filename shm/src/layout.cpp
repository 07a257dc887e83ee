// Implements layout.hpp: layout of one controller instance's shared-memory segment.
#include "hapticctrl/shm/layout.hpp"

namespace hapticctrl::shm {

std::string_view region_name(RegionId id) noexcept {
  switch (id) {
    case RegionId::kVpr:
      return "VPr";
    case RegionId::kVp:
      return "VP";
    case RegionId::kForce:
      return "force";
    case RegionId::kPosition:
      return "position";
    case RegionId::kCtrl:
      return "ctrl";
    case RegionId::kCtrlAck:
      return "ctrl_ack";
    case RegionId::kTelemetry:
      return "telemetry";
    case RegionId::kLinkStats:
      return "link_stats";
    case RegionId::kEvents:
      return "events";
    case RegionId::kBlackBox:
      return "blackbox";
    case RegionId::kCount:
      break;
  }
  return "?";
}

}  // namespace hapticctrl::shm
