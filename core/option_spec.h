// One description per option of a settings struct (key, type, unit, range,
// default, help), from which every front end is made: the CLI11 flags
// (app/commands/option_flags.h), the YAML sections of settings files
// (ReadOptionEntries below), the GUI forms (ui/option_form.h) and the tables
// in docs/cli.md (OptionsMarkdownTable, checked by a test). The default is
// the struct's own in-class initialiser, so adding an option is one entry.
//
//   const OptionTable<NoiseModel>& table = NoiseModelOptions();
//   NoiseModel noise;
//   Status s = ApplyOptionText(FindOption(table, "leg"), "0.002", &noise, "plan.yaml: noise.leg");
#pragma once

#include <charconv>
#include <cmath>
#include <functional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/csv.h"
#include "core/status.h"

namespace hexcal {

// kChoiceList: one or more of the choices, as "a,b" in text (a repeated CLI flag).
// kText: free text whose form the step that takes it checks ("8:41", a list
// of names and files), naming the option by its key (Status::BadOption).
enum class OptionType { kInteger, kNumber, kFlag, kChoice, kChoiceList, kText };

// The most threads a --threads option takes (0 = every core): a typo such as
// 100000 must stop at once (issue 13).
constexpr int kMaxThreads = 256;

// 2^53: the largest integer every smaller one of which a double holds
// exactly, and so the bound of a seed, which is read as a double.
constexpr double kMaxExactInteger = 9007199254740992.0;

template <typename T>
struct OptionSpec {
  std::string key;    // YAML key; the CLI flag is `flag`, or "--" + key with '_' as '-'
  std::string label;  // GUI label
  OptionType type = OptionType::kNumber;
  std::string unit;        // shown after the value ("" for none)
  double min = 0, max = 0;  // inclusive range of a number or integer
  std::string help;         // one sentence a user can act on
  std::vector<std::string> choices;  // kChoice, kChoiceList: the accepted names
  // A number that may be left unset (get_number gives NaN then): what
  // applies instead ("the controller's"). Empty: the value is always set.
  std::string unset;
  // Numbers, integers and flags (1/0) read and write through these ...
  std::function<double(const T&)> get_number;
  std::function<void(T&, double)> set_number;
  // ... choices, comma-joined choice lists and text through these.
  std::function<std::string(const T&)> get_choice;
  std::function<void(T&, const std::string&)> set_choice;
  std::string flag;  // CLI flag when it is not derived from the key
  bool file_allowed = false;  // kChoice: any other value is taken as a file name

  std::string Flag(const std::string& prefix = "") const {
    if (!flag.empty()) return "--" + prefix + flag;
    std::string name = key;
    for (char& c : name) c = c == '_' ? '-' : c;
    return "--" + prefix + name;
  }
};

template <typename T>
using OptionTable = std::vector<OptionSpec<T>>;

// A numeric option (kInteger, kNumber or kFlag) bound to the field of T that
// `field` returns by reference: its value is read and written as a double.
//
//   NumberOption<PlannerOptions>("keep", "Keep on primary", OptionType::kNumber, "fraction", 0.01, 1,
//                                "...", [](PlannerOptions& o) -> double& { return o.keep; });
template <typename T, typename Field>
OptionSpec<T> NumberOption(std::string key, std::string label, OptionType type, std::string unit, double min,
                           double max, std::string help, Field field) {
  OptionSpec<T> spec;
  spec.key = std::move(key);
  spec.label = std::move(label);
  spec.type = type;
  spec.unit = std::move(unit);
  spec.min = min;
  spec.max = max;
  spec.help = std::move(help);
  spec.get_number = [field](const T& s) { return static_cast<double>(field(const_cast<T&>(s))); };
  spec.set_number = [field](T& s, double v) {
    auto& target = field(s);
    target = static_cast<std::remove_reference_t<decltype(target)>>(v);
  };
  return spec;
}

// A random seed, 0 to 2^53, bound to a uint64_t field; `help` says what it seeds.
template <typename T, typename Field>
OptionSpec<T> SeedOption(std::string help, Field field) {
  return NumberOption<T>("seed", "Seed", OptionType::kInteger, "", 0, kMaxExactInteger, std::move(help), field);
}

// A thread count, 0 (every core) to kMaxThreads, bound to an int field.
template <typename T, typename Field>
OptionSpec<T> ThreadsOption(std::string label, std::string help, Field field) {
  return NumberOption<T>("threads", std::move(label), OptionType::kInteger, "threads", 0, kMaxThreads,
                         std::move(help), field);
}

// A choice (kChoice) or a list of choices (kChoiceList, "a,b") read and
// written as text through `get` and `set`.
template <typename T>
OptionSpec<T> ChoiceOption(std::string key, std::string label, OptionType type, std::vector<std::string> choices,
                           std::string help, std::function<std::string(const T&)> get,
                           std::function<void(T&, const std::string&)> set) {
  OptionSpec<T> spec;
  spec.key = std::move(key);
  spec.label = std::move(label);
  spec.type = type;
  spec.choices = std::move(choices);
  spec.help = std::move(help);
  spec.get_choice = std::move(get);
  spec.set_choice = std::move(set);
  return spec;
}

// A number option that may be left unset, bound to a std::optional field of
// T; `unset` says what applies then ("the controller's").
//
//   OptionalNumberOption<AcquireOptions>("settle", "Settle time", "s", 0, 600, "...", "the controller's",
//                                        [](AcquireOptions& o) -> std::optional<double>& { return o.settle_seconds; });
template <typename T, typename Field>
OptionSpec<T> OptionalNumberOption(std::string key, std::string label, std::string unit, double min, double max,
                                   std::string help, std::string unset, Field field) {
  OptionSpec<T> spec;
  spec.key = std::move(key);
  spec.label = std::move(label);
  spec.type = OptionType::kNumber;
  spec.unit = std::move(unit);
  spec.min = min;
  spec.max = max;
  spec.help = std::move(help);
  spec.unset = std::move(unset);
  spec.get_number = [field](const T& s) { return field(const_cast<T&>(s)).value_or(std::nan("")); };
  spec.set_number = [field](T& s, double v) { field(s) = v; };
  return spec;
}

// A text option bound to a std::string field of T.
template <typename T, typename Field>
OptionSpec<T> TextOption(std::string key, std::string label, std::string help, Field field) {
  OptionSpec<T> spec;
  spec.key = std::move(key);
  spec.label = std::move(label);
  spec.type = OptionType::kText;
  spec.help = std::move(help);
  spec.get_choice = [field](const T& s) { return field(const_cast<T&>(s)); };
  spec.set_choice = [field](T& s, const std::string& v) { field(s) = v; };
  return spec;
}

// Whether the option has a value in `values` (an optional number may not).
template <typename T>
bool OptionIsSet(const OptionSpec<T>& spec, const T& values) {
  return spec.unset.empty() || !std::isnan(spec.get_number(values));
}

// The flag a user types: a flag option that is on by default is turned off
// with --no-KEY.
template <typename T>
std::string OptionCliFlag(const OptionSpec<T>& spec, const std::string& prefix = "") {
  if (spec.type == OptionType::kFlag && spec.get_number(T{}) != 0) return "--" + prefix + "no-" + spec.Flag().substr(2);
  return spec.Flag(prefix);
}

// The spec of `key`, or nullptr.
template <typename T>
const OptionSpec<T>* FindOption(const OptionTable<T>& table, const std::string& key) {
  for (const OptionSpec<T>& spec : table)
    if (spec.key == key) return &spec;
  return nullptr;
}

// The value of one option as text: numbers in their shortest exact form, ""
// for an optional number that is not set.
template <typename T>
std::string OptionText(const OptionSpec<T>& spec, const T& values) {
  if (spec.type == OptionType::kChoice || spec.type == OptionType::kChoiceList || spec.type == OptionType::kText)
    return spec.get_choice(values);
  if (!OptionIsSet(spec, values)) return "";
  const double value = spec.get_number(values);
  if (spec.type == OptionType::kFlag) return value != 0 ? "true" : "false";
  return FormatNumber(value);
}

// Parses `text` by the option's type, checks the range or the choices and
// sets it; the error starts with `where` (a flag, a file and key, a label).
inline std::vector<std::string> SplitOptionList(const std::string& text) {
  std::vector<std::string> items;
  std::string item;
  for (char c : text + ",") {
    if (c != ',') {
      if (c != ' ') item += c;
      continue;
    }
    items.push_back(item);
    item.clear();
  }
  return items;
}

template <typename T>
Status CheckChoices(const OptionSpec<T>& spec, const std::vector<std::string>& items, const std::string& where) {
  for (const std::string& item : items) {
    if (spec.file_allowed && !item.empty()) continue;
    bool known = false;
    for (const std::string& choice : spec.choices) known = known || choice == item;
    if (known) continue;
    std::string names;
    for (const std::string& choice : spec.choices) names += (names.empty() ? "" : ", ") + choice;
    return Status::BadInput(where + ": expected " +
                            (spec.type == OptionType::kChoiceList ? "one or more of " : "one of ") + names);
  }
  return Status::Ok();
}

// An integer option's text: plain decimal digits ("1e3", "10.0" and "0x10"
// are refused) that a double holds exactly. A double rounds 9007199254740993
// to ...992, which then passed a range ending at 2^53 (study --seed, issue 36):
// such a number is beyond every integer option's range, on its side of zero.
inline Status CheckIntegerText(const std::string& text, double value, double min, double max, const std::string& where,
                               const std::string& unit) {
  const size_t sign = !text.empty() && (text[0] == '+' || text[0] == '-') ? 1 : 0;
  long long exact = 0;
  const char* last = text.data() + text.size();
  const auto [end, error] = std::from_chars(text.data() + (sign && text[0] == '+' ? 1 : 0), last, exact);
  if (text.size() == sign || end != last || (error != std::errc() && error != std::errc::result_out_of_range))
    return Status::BadInput(where + ": expected a whole number in decimal digits, got " + Excerpt(text));
  if (error == std::errc() && std::abs(value) <= kMaxExactInteger && static_cast<long long>(value) == exact)
    return Status::Ok();
  if (value < 0) return Status::BadInput(where + ": must be at least " + FormatNumber(min) + unit + ", got " + text);
  return Status::BadInput(where + ": must be at most " + FormatNumber(max) + unit + ", got " + text);
}

// What is wrong with a number against the option's inclusive range
// ("must be at most 600 s, got 900"), or "" when it is within.
template <typename T>
std::string OptionRangeProblem(const OptionSpec<T>& spec, double value) {
  const std::string unit = spec.unit.empty() ? "" : " " + spec.unit;
  if (!(value >= spec.min)) return "must be at least " + FormatNumber(spec.min) + unit + ", got " + FormatNumber(value);
  if (!(value <= spec.max)) return "must be at most " + FormatNumber(spec.max) + unit + ", got " + FormatNumber(value);
  return "";
}

// A number against the option's inclusive range; the error starts with `where`.
template <typename T>
Status CheckOptionRange(const OptionSpec<T>& spec, double value, const std::string& where) {
  const std::string problem = OptionRangeProblem(spec, value);
  return problem.empty() ? Status::Ok() : Status::BadInput(where + ": " + problem);
}

// The range as the docs show it: "7 – 100000", "≥ 0".
template <typename T>
std::string OptionRangeText(const OptionSpec<T>& spec) {
  return std::isinf(spec.max) ? "≥ " + FormatNumber(spec.min) : FormatNumber(spec.min) + " – " + FormatNumber(spec.max);
}

template <typename T>
Status ApplyOptionText(const OptionSpec<T>& spec, const std::string& text, T* values, const std::string& where) {
  if (spec.type == OptionType::kText) {
    spec.set_choice(*values, text);
    return Status::Ok();
  }
  if (spec.type == OptionType::kChoice || spec.type == OptionType::kChoiceList) {
    const std::vector<std::string> items =
        spec.type == OptionType::kChoice ? std::vector<std::string>{text} : SplitOptionList(text);
    if (Status s = CheckChoices(spec, items, where); !s.ok()) return s;
    spec.set_choice(*values, text);
    return Status::Ok();
  }
  if (spec.type == OptionType::kFlag) {
    if (text == "true" || text == "1") spec.set_number(*values, 1);
    else if (text == "false" || text == "0") spec.set_number(*values, 0);
    else
      return Status::BadInput(where + ": expected true or false");
    return Status::Ok();
  }
  StatusOr<double> value = ParseNumber(text);
  if (!value.ok()) return Status::BadInput(where + ": expected a finite number, got " + Excerpt(text));
  if (spec.type == OptionType::kInteger && *value != std::floor(*value))
    return Status::BadInput(where + ": expected a whole number, got " + FormatNumber(*value));
  if (spec.type == OptionType::kInteger) {
    const std::string unit = spec.unit.empty() ? "" : " " + spec.unit;
    if (Status s = CheckIntegerText(text, *value, spec.min, spec.max, where, unit); !s.ok()) return s;
  }
  if (Status s = CheckOptionRange(spec, *value, where); !s.ok()) return s;
  spec.set_number(*values, *value);
  return Status::Ok();
}

// The range check of a numeric option's value that code set rather than text
// gave: a core IsValid checks its struct against the descriptor the CLI, the
// settings files and the GUI read the option with, so the range is written
// once (issue 37). The error names the option by its key
// (Status::BadOption), for each front end to show in its own words. NaN is
// out of every range; an optional number that is not set is in it.
template <typename T>
Status CheckOptionRanges(const OptionTable<T>& table, const T& values) {
  for (const OptionSpec<T>& spec : table) {
    if (spec.type != OptionType::kInteger && spec.type != OptionType::kNumber) continue;
    if (!OptionIsSet(spec, values)) continue;
    const std::string problem = OptionRangeProblem(spec, spec.get_number(values));
    if (!problem.empty()) return Status::BadOption(spec.key, problem);
  }
  return Status::Ok();
}

// An option of a struct held inside another (`Inner` in `Outer`, reached
// through `inner`): the same key, range, help and choices, read and written
// through the outer struct. A front end's table takes a lower layer's
// option whole instead of restating its range.
template <typename Outer, typename Inner, typename Access>
OptionSpec<Outer> NestedOption(const OptionSpec<Inner>& spec, Access inner) {
  OptionSpec<Outer> nested;
  nested.key = spec.key;
  nested.label = spec.label;
  nested.type = spec.type;
  nested.unit = spec.unit;
  nested.min = spec.min;
  nested.max = spec.max;
  nested.help = spec.help;
  nested.choices = spec.choices;
  nested.unset = spec.unset;
  nested.flag = spec.flag;
  nested.file_allowed = spec.file_allowed;
  if (spec.get_number) {
    nested.get_number = [get = spec.get_number, inner](const Outer& o) { return get(inner(const_cast<Outer&>(o))); };
    nested.set_number = [set = spec.set_number, inner](Outer& o, double v) { set(inner(o), v); };
  }
  if (spec.get_choice) {
    nested.get_choice = [get = spec.get_choice, inner](const Outer& o) { return get(inner(const_cast<Outer&>(o))); };
    nested.set_choice = [set = spec.set_choice, inner](Outer& o, const std::string& v) { set(inner(o), v); };
  }
  return nested;
}

// Applies the (key, text) entries of a settings-file section; an unknown key
// is an error that lists the known ones. `section` names it ("plan.yaml: planner").
template <typename T>
Status ApplyOptionEntries(const OptionTable<T>& table, const std::vector<std::pair<std::string, std::string>>& entries,
                          T* values, const std::string& section) {
  for (const auto& [key, text] : entries) {
    const OptionSpec<T>* spec = FindOption(table, key);
    if (spec == nullptr) {
      std::string keys;
      for (const OptionSpec<T>& known : table) keys += (keys.empty() ? "" : ", ") + known.key;
      const std::string shown = IsPlainName(key) ? key : "(a key that is not a name)";
      return Status::BadInput(section + "." + shown + ": unknown key (" + keys + ")");
    }
    if (Status s = ApplyOptionText(*spec, text, values, section + "." + key); !s.ok()) return s;
  }
  return Status::Ok();
}

// The docs table: | key | flag | type | unit | range | default | meaning |.
template <typename T>
std::string OptionsMarkdownTable(const OptionTable<T>& table, const std::string& flag_prefix = "") {
  static const char* kTypeNames[] = {"integer", "number", "flag", "choice", "list of choices", "text"};
  const T defaults{};
  std::string text = "| key | flag | type | unit | range | default | meaning |\n|---|---|---|---|---|---|---|\n";
  for (const OptionSpec<T>& spec : table) {
    std::string range;
    if (spec.type == OptionType::kChoice || spec.type == OptionType::kChoiceList) {
      for (const std::string& choice : spec.choices) range += (range.empty() ? "" : ", ") + choice;
    } else if (spec.type == OptionType::kInteger || spec.type == OptionType::kNumber) {
      range = OptionRangeText(spec);
    }
    const std::string value = OptionIsSet(spec, defaults) ? OptionText(spec, defaults) : spec.unset;
    text += "| `" + spec.key + "` | `" + OptionCliFlag(spec, flag_prefix) + "` | " +
            kTypeNames[static_cast<int>(spec.type)] + " | " + spec.unit + " | " + range + " | " + value + " | " +
            spec.help + " |\n";
  }
  return text;
}

}  // namespace hexcal
