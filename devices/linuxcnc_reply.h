// Reading linuxcncrsh's replies (devices/linuxcnc_controller.h): words,
// keys compared without case, numbers that must be finite. Shared by the
// controller and the read-only follower of sim/machine_follower.h.
//
//   std::vector<std::string> words = ReplyWords("JOINT_POS 1 2 3 4 5 6");
//   std::optional<Vector6d> joints = SixNumbersAfter("JOINT_POS", reply);
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/robot.h"

namespace hexcal::workflow {

std::string UpperCase(std::string text);
// The words of a reply, split at white space.
std::vector<std::string> ReplyWords(const std::string& line);
std::string JoinWords(const std::vector<std::string>& words);
// Whole-string parse of a finite number.
bool ParseFiniteNumber(const std::string& text, double* value);
// The six numbers of "KEY n1 .. n6" (KEY in any case); nullopt when the reply
// has another key, another count or a word that is not a finite number.
std::optional<Vector6d> SixNumbersAfter(const std::string& key, const std::string& reply);

}  // namespace hexcal::workflow
