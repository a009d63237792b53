#include "devices/linuxcnc_ini.h"

#include <gtest/gtest.h>

#include <string>

namespace hexcal::workflow {
namespace {

// An INI as scripts/linuxcnc-sim.sh writes it, trimmed to what matters.
std::string SampleIni() {
  std::string text = "# a comment\n[TRAJ]\nLINEAR_UNITS = mm\nHOME = 0 0 535 0 0 0\n[HAL]\n"
                     "HALFILE = LIB:basic_sim.tcl -no_sim_spindle\nHALFILE = genhexkins.hal\n";
  for (int n = 0; n < 6; ++n) {
    const std::string joint = std::to_string(600 + n) + ".5";
    text += "[JOINT_" + std::to_string(n) + "]\nTYPE = LINEAR\nHOME = " + joint + "\nHOME_OFFSET =  " + joint +
            "\nMIN_LIMIT = 500\nMAX_LIMIT = 700.25\nMAX_VELOCITY = 200\n";
  }
  return text + "[AXIS_X]\nMIN_LIMIT = -100000\n";
}

TEST(LinuxCncIni, ReadsTheJointHomesLimitsUnitAndHalFiles) {
  StatusOr<MachineIni> ini = ParseMachineIni(SampleIni());
  ASSERT_TRUE(ini.ok()) << ini.status().message();
  EXPECT_EQ(ini->unit, MachineUnit::kMillimetre);
  EXPECT_EQ(ini->joints[3].home, 603.5);
  EXPECT_EQ(ini->joints[3].home_offset, 603.5);
  EXPECT_EQ(ini->joints[5].min_limit, 500);
  EXPECT_EQ(ini->joints[5].max_limit, 700.25);
  ASSERT_EQ(ini->hal_files.size(), 2u);
  EXPECT_EQ(ini->hal_files[1], "genhexkins.hal");
}

TEST(LinuxCncIni, ShiftingChangesOnlyTheFourValuesOfEachJoint) {
  StatusOr<MachineIni> ini = ParseMachineIni(SampleIni());
  ASSERT_TRUE(ini.ok());
  const std::string shifted = ShiftedIniText(*ini, {0, 0.125, 0, 0, 0, -1.0 / 3.0});
  StatusOr<MachineIni> again = ParseMachineIni(shifted);
  ASSERT_TRUE(again.ok()) << again.status().message();
  EXPECT_EQ(again->joints[1].home, 601.625);
  EXPECT_EQ(again->joints[1].home_offset, 601.625);
  EXPECT_EQ(again->joints[1].max_limit, 700.375);
  EXPECT_EQ(again->joints[5].min_limit, 500 - 1.0 / 3.0);  // full precision
  EXPECT_EQ(again->joints[0].home, 600.5);
  EXPECT_NE(shifted.find("HOME_OFFSET =  601.625\n"), std::string::npos) << shifted;  // spacing kept
  EXPECT_NE(shifted.find("[AXIS_X]\nMIN_LIMIT = -100000\n"), std::string::npos);        // not a joint's
  EXPECT_NE(shifted.find("HOME = 0 0 535 0 0 0\n"), std::string::npos);                 // [TRAJ] HOME
  EXPECT_EQ(ShiftedIniText(*ini, {}), SampleIni());
  const std::string changes = IniChangeText(*ini, {0, 0.125, 0, 0, 0, 0});
  EXPECT_EQ(changes.rfind("[JOINT_1] HOME 601.5 -> 601.625\n", 0), 0u) << changes;
}

TEST(LinuxCncIni, BadInisNameTheSectionAndKey) {
  const auto error = [](const std::string& text) { return ParseMachineIni(text).status().message(); };
  std::string text = SampleIni();
  EXPECT_NE(error(text + "[JOINT_2]\nHOME = 1\n").find("[JOINT_2] HOME is given twice"), std::string::npos);
  std::string hex = text;
  hex.replace(hex.find("MAX_LIMIT = 700.25"), 18, "MAX_LIMIT = 0x2bc");
  EXPECT_NE(error(hex).find("[JOINT_0] MAX_LIMIT is not a decimal number"), std::string::npos) << error(hex);
  std::string inch = text;
  inch.replace(inch.find("LINEAR_UNITS = mm"), 17, "LINEAR_UNITS = cm");
  EXPECT_NE(error(inch).find("LINEAR_UNITS is not mm or inch"), std::string::npos);
  const std::string five = text.substr(0, text.find("[JOINT_5]"));
  EXPECT_NE(error(five).find("no [JOINT_5] HOME"), std::string::npos) << error(five);
  EXPECT_NE(error("[JOINT_0]\nHOME = 1\n").find("no [TRAJ] LINEAR_UNITS"), std::string::npos);
}

}  // namespace
}  // namespace hexcal::workflow
