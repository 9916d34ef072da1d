#include "model/vehicle.h"

#include <cassert>

namespace slipgraph {

const char* VehicleTypeName(VehicleType type) {
  switch (type) {
    case VehicleType::kDiffDriveCastor:
      return "diff_drive_castor";
    case VehicleType::kSkidSteer:
      return "skid_steer";
    case VehicleType::kRockerBogie6:
      return "rocker_bogie6";
  }
  return "unknown";
}

bool ParseVehicleType(const std::string& name, VehicleType* type) {
  for (VehicleType candidate :
       {VehicleType::kDiffDriveCastor, VehicleType::kSkidSteer, VehicleType::kRockerBogie6}) {
    if (name == VehicleTypeName(candidate)) {
      *type = candidate;
      return true;
    }
  }
  return false;
}

const std::vector<std::string>& WheelNames(VehicleType type) {
  static const std::vector<std::string> kTwoSides = {"left", "right"};
  static const std::vector<std::string> kSixWheels = {"fl", "ml", "rl", "fr", "mr", "rr"};
  return type == VehicleType::kRockerBogie6 ? kSixWheels : kTwoSides;
}

int WheelSide(const std::string& wheel_name) {
  if (wheel_name == "left" || (wheel_name.size() == 2 && wheel_name[1] == 'l')) return +1;
  assert(wheel_name == "right" || (wheel_name.size() == 2 && wheel_name[1] == 'r'));
  return -1;
}

}  // namespace slipgraph
