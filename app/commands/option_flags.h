// CLI11 flags made from an option table (core/option_spec.h): one flag per
// option, with its help, unit, range check and default; a flag the user gives
// appends (key, value) to `entries`, which the workflow step applies over
// the defaults and any settings file (workflow/plan_step.h). A flag option
// whose default is true is offered as --no-KEY.
//
//   workflow::OptionEntries planner;
//   AddOptionFlags(sub, workflow::PlanSetupOptions(), &planner);
//   AddOptionFlags(sub, NoiseModelOptions(), &noise, "noise-");
#pragma once

#include <CLI/CLI.hpp>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/option_spec.h"

namespace hexcal::cli {

using OptionEntries = std::vector<std::pair<std::string, std::string>>;

template <typename T>
CLI::Option* AddOneOptionFlag(CLI::App* sub, const OptionSpec<T>& spec, std::shared_ptr<OptionEntries> entries,
                              const std::string& prefix) {
  const T defaults{};
  const std::string key = spec.key;
  const std::string help = spec.help + (spec.unit.empty() ? "" : " (" + spec.unit + ")");
  if (spec.type == OptionType::kFlag) {
    const bool on_by_default = spec.get_number(defaults) != 0;
    const std::string value = on_by_default ? "false" : "true";
    return sub->add_flag_callback(OptionCliFlag(spec, prefix), [entries, key, value] { entries->emplace_back(key, value); },
                                  on_by_default ? "do not: " + help : help);
  }
  if (spec.type == OptionType::kChoiceList) {
    return sub
        ->add_option_function<std::vector<std::string>>(
            spec.Flag(prefix),
            [entries, key](const std::vector<std::string>& values) {
              std::string joined;
              for (const std::string& v : values) joined += (joined.empty() ? "" : ",") + v;
              entries->emplace_back(key, joined);
            },
            help + "; repeat to pool")
        ->type_name("NAME")
        ->check(CLI::IsMember(spec.choices))
        ->default_str(OptionText(spec, defaults));
  }
  CLI::Option* option = sub->add_option_function<std::string>(
      spec.Flag(prefix), [entries, key](const std::string& value) { entries->emplace_back(key, value); }, help);
  if (spec.type == OptionType::kChoice) {
    option->type_name(spec.file_allowed ? "NAME|FILE" : "NAME");
    if (!spec.file_allowed) option->check(CLI::IsMember(spec.choices));
    return option->default_str(OptionText(spec, defaults));
  }
  option->check([spec](const std::string& text) {
    T scratch{};
    const Status s = ApplyOptionText(spec, text, &scratch, "");
    return s.ok() ? std::string() : s.message().substr(2);  // CLI11 names the flag
  });
  option->type_name(spec.type == OptionType::kInteger ? "INT" : "NUMBER");
  return option->default_str(OptionText(spec, defaults));
}

// Adds every option of `table`; the flags given fill `*entries` in command-line order.
template <typename T>
void AddOptionFlags(CLI::App* sub, const OptionTable<T>& table, std::shared_ptr<OptionEntries> entries,
                    const std::string& prefix = "") {
  for (const OptionSpec<T>& spec : table) AddOneOptionFlag(sub, spec, entries, prefix);
}

}  // namespace hexcal::cli
