// Shared by the benchmarks: the robot they time, loaded once, before any timing.
#pragma once

#include "core/robot_io.h"

namespace hexcal::bench {

// The paper's INRIA robot (the inria-left-hand preset).
inline const Robot& Inria() {
  static const Robot robot = *LoadRobot("inria-left-hand");
  return robot;
}

}  // namespace hexcal::bench
