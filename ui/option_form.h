// GUI form rows made from an option table (core/option_spec.h): a spin box
// with the option's range and unit, a check box, a combo box (editable where
// a file name is allowed), one check box per choice or a line of text, each
// with the option's help as tooltip. Reading the form back goes through the
// same ApplyOptionText as the CLI and the settings files, so an option is
// spelled once; a lower layer's error about one of the options names it by
// its label (WithOptionLabel), as the form does.
//
//   OptionRows rows = AddOptionRows(form_layout, NoiseModelOptions(), NoiseModel{});
//   StatusOr<NoiseModel> noise = ReadOptionRows(NoiseModelOptions(), rows);
//   ShowError(this, "Plan", QString::fromStdString(WithOptionLabel(status, table).message()));
#pragma once

#include <QString>
#include <functional>
#include <map>
#include <string>

#include "core/option_spec.h"

class QFormLayout;
class QWidget;

namespace hexcal::ui {

// The widget of one option: its value as text, both ways.
struct OptionRow {
  QWidget* widget = nullptr;
  std::function<std::string()> text;
  std::function<void(const std::string&)> set_text;
};
using OptionRows = std::map<std::string, OptionRow>;  // by key

// The widget for one option, set to `value` (text form); objectName is the key.
// A spin box has no "not set": an optional number (OptionSpec::unset, the
// Acquire step's settle time) gets no form row until a form needs one.
OptionRow MakeOptionRow(OptionType type, const std::string& key, const std::string& unit, double min, double max,
                        const std::vector<std::string>& choices, bool editable, const QString& tooltip,
                        const std::string& value);

template <typename T>
OptionRows AddOptionRows(QFormLayout* form, const OptionTable<T>& table, const T& values);

template <typename T>
StatusOr<T> ReadOptionRows(const OptionTable<T>& table, const OptionRows& rows, T values = T{}) {
  for (const OptionSpec<T>& spec : table) {
    auto it = rows.find(spec.key);
    if (it == rows.end()) continue;
    if (Status s = ApplyOptionText(spec, it->second.text(), &values, spec.label); !s.ok()) return s;
  }
  return values;
}

void AddFormRow(QFormLayout* form, const QString& label, const QString& tooltip, QWidget* widget);

// `status` in the GUI's words: an error about an option of `table`
// (Status::option(), its key) names the option by its label, "Poses per
// subset (N): 20 needs more than ...", as ReadOptionRows does.
template <typename T>
Status WithOptionLabel(const Status& status, const OptionTable<T>& table) {
  const OptionSpec<T>* spec = FindOption(table, status.option());
  return spec == nullptr ? status : status.WithOptionName(spec->label);
}

template <typename T>
OptionRows AddOptionRows(QFormLayout* form, const OptionTable<T>& table, const T& values) {
  OptionRows rows;
  for (const OptionSpec<T>& spec : table) {
    const QString tooltip = QString::fromStdString(spec.help);
    OptionRow row = MakeOptionRow(spec.type, spec.key, spec.unit, spec.min, spec.max, spec.choices,
                                  spec.file_allowed, tooltip, OptionText(spec, values));
    AddFormRow(form, QString::fromStdString(spec.label), tooltip, row.widget);
    rows[spec.key] = row;
  }
  return rows;
}

}  // namespace hexcal::ui
