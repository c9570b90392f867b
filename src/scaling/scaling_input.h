#pragma once
#include <map>
#include <optional>
#include <string>

#include "machine/machine_profile.h"
#include "model/gear_model.h"
#include "model/gear_state.h"
#include "scaling/maxima.h"

namespace gearpatch {

/// Everything the scaling takes from a scene, typed: the gear and its drive,
/// where the run starts and how long it lasts, the drive's rated data, the
/// [maxima] overrides and the machine. The scene module fills it
/// (scene_inputs.h); the layers below never see the scene file.
struct ScalingInput {
  std::string name;           ///< the scene's name, for reports
  GearParameters gear;
  GearState initial;          ///< φ̇p(0), φ̇s(0), Δφ(0)
  double duration = 1;        ///< s of real time
  std::optional<double> rated_torque;  ///< M_am from the drive's data
  std::optional<double> rated_speed;   ///< φ̇pm = φ̇sm from the drive's data
  std::map<Maximum, double> maxima;  ///< overrides of the a-priori maxima
  MachineProfile machine;
};

}  // namespace gearpatch
