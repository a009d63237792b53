// CLI11 flags made from an option table (core/option_spec.h): one flag per
// option, with its help, unit, range check (shown in --help) and default; a
// flag the user gives appends (key, value) to `entries`, which the command or
// its workflow step applies over the defaults and any settings file
// (workflow/plan_step.h). A flag option whose default is true is offered as
// --no-KEY. Each flag is recorded in `names` under its key, so that a lower
// layer's error about an option (Status::option(), the key) is shown with the
// flag the user typed (ReportError in cli_common.h).
//
//   workflow::OptionEntries planner;
//   OptionFlagNames flags;
//   AddOptionFlags(sub, workflow::PlanSetupOptions(), &planner, &flags);
//   AddOptionFlags(sub, NoiseModelOptions(), &noise, &flags, "noise-");
//   ...
//   return ReportError(err, "plan", status, flags);  // "hexcal plan: --init: ..."
#pragma once

#include <CLI/CLI.hpp>
#include <cassert>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "app/commands/cli_common.h"
#include "core/option_spec.h"

namespace hexcal::cli {

using OptionEntries = std::vector<std::pair<std::string, std::string>>;

// The range a number or integer flag takes, as its --help shows it after the type.
template <typename T>
std::string FlagRangeText(const OptionSpec<T>& spec) {
  const std::string type = spec.type == OptionType::kInteger ? "INT" : "NUMBER";
  if (std::isinf(spec.max)) return type + " >= " + FormatNumber(spec.min);
  return type + " in [" + FormatNumber(spec.min) + ", " + FormatNumber(spec.max) + "]";
}

template <typename T>
CLI::Option* AddOneOptionFlag(CLI::App* sub, const OptionSpec<T>& spec, std::shared_ptr<OptionEntries> entries,
                              OptionFlagNames* names, const std::string& prefix = "") {
  const T defaults{};
  const std::string key = spec.key;
  // One key, one flag in a command: the lower layers name the option by its key.
  assert(names->count(key) == 0 || names->at(key) == OptionCliFlag(spec, prefix));
  (*names)[key] = OptionCliFlag(spec, prefix);
  const std::string help = spec.help + (spec.unit.empty() ? "" : " (" + spec.unit + ")") +
                           (spec.unset.empty() ? "" : "; default: " + spec.unset);
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
  if (spec.type == OptionType::kText) return option->type_name("TEXT")->default_str(OptionText(spec, defaults));
  if (spec.type == OptionType::kChoice) {
    option->type_name(spec.file_allowed ? "NAME|FILE" : "NAME");
    if (!spec.file_allowed) option->check(CLI::IsMember(spec.choices));
    return option->default_str(OptionText(spec, defaults));
  }
  option->check(
      [spec](const std::string& text) {
        T scratch{};
        const Status s = ApplyOptionText(spec, text, &scratch, "");
        return s.ok() ? std::string() : s.message().substr(2);  // CLI11 names the flag
      },
      FlagRangeText(spec));
  option->type_name(spec.type == OptionType::kInteger ? "INT" : "NUMBER");
  return option->default_str(OptionText(spec, defaults));
}

// Adds every option of `table`; the flags given fill `*entries` in command-line order.
template <typename T>
void AddOptionFlags(CLI::App* sub, const OptionTable<T>& table, std::shared_ptr<OptionEntries> entries,
                    OptionFlagNames* names, const std::string& prefix = "") {
  for (const OptionSpec<T>& spec : table) AddOneOptionFlag(sub, spec, entries, names, prefix);
}

// Whether the command line gave the option `key` (its entries hold it).
inline bool OptionGiven(const OptionEntries& entries, const std::string& key) {
  for (const auto& entry : entries)
    if (entry.first == key) return true;
  return false;
}

}  // namespace hexcal::cli
