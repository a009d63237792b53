#include "ui/option_form.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QLabel>
#include <QLineEdit>
#include <QVBoxLayout>
#include <algorithm>
#include <cmath>

#include "core/csv.h"

namespace hexcal::ui {
namespace {

// Enough decimals to show `value` exactly and one more to edit it, at least 2.
int DecimalsFor(double value) {
  int needed = 0;
  while (needed < 6 && std::abs(value * std::pow(10.0, needed) - std::round(value * std::pow(10.0, needed))) > 1e-9)
    ++needed;
  return std::max(2, std::min(6, needed + 1));
}

OptionRow NumberRow(OptionType type, const std::string& unit, double min, double max, const std::string& value) {
  auto* spin = new QDoubleSpinBox;
  spin->setRange(min, std::min(max, 1e12));
  StatusOr<double> initial = ParseNumber(value);
  spin->setDecimals(type == OptionType::kInteger ? 0 : DecimalsFor(initial.ok() ? *initial : 0));
  if (type == OptionType::kNumber) spin->setSingleStep(max - min <= 1 ? 0.05 : 1);
  if (!unit.empty()) spin->setSuffix(QString(" ") + QString::fromStdString(unit));
  // A count's unit in the right number: "1 pose", "4 poses" (not "1 poses").
  const QString plural = QString::fromStdString(unit);
  if (type == OptionType::kInteger && plural.endsWith('s'))
    QObject::connect(spin, qOverload<double>(&QDoubleSpinBox::valueChanged), spin, [spin, plural](double v) {
      spin->setSuffix(" " + (v == 1 ? plural.chopped(1) : plural));
    });
  spin->setValue(initial.ok() ? *initial : min);
  if (type == OptionType::kInteger && plural.endsWith('s') && spin->value() == 1) spin->setSuffix(" " + plural.chopped(1));
  return {spin, [spin] { return FormatNumber(spin->value()); },
          [spin](const std::string& text) {
            StatusOr<double> v = ParseNumber(text);
            if (v.ok()) spin->setValue(*v);
          }};
}

OptionRow ChoiceRow(const std::vector<std::string>& choices, bool editable, const std::string& value) {
  auto* box = new QComboBox;
  for (const std::string& choice : choices) box->addItem(QString::fromStdString(choice));
  box->setEditable(editable);
  box->setCurrentText(QString::fromStdString(value));
  return {box, [box] { return box->currentText().toStdString(); },
          [box](const std::string& text) { box->setCurrentText(QString::fromStdString(text)); }};
}

// One check box per choice, one under the other (a narrow form stays
// readable); the text is the checked ones, comma-joined.
OptionRow ChoiceListRow(const std::vector<std::string>& choices, const std::string& value) {
  auto* group = new QWidget;
  auto* layout = new QVBoxLayout(group);
  layout->setContentsMargins(0, 0, 0, 0);
  std::vector<std::pair<std::string, QCheckBox*>> boxes;
  for (const std::string& choice : choices) {
    auto* box = new QCheckBox(QString::fromStdString(choice));
    box->setObjectName(QString::fromStdString(choice));
    layout->addWidget(box);
    boxes.emplace_back(choice, box);
  }
  const auto set_text = [boxes](const std::string& text) {
    const std::vector<std::string> items = SplitOptionList(text);
    for (const auto& [choice, box] : boxes)
      box->setChecked(std::find(items.begin(), items.end(), choice) != items.end());
  };
  set_text(value);
  return {group,
          [boxes] {
            std::string text;
            for (const auto& [choice, box] : boxes)
              if (box->isChecked()) text += (text.empty() ? "" : ",") + choice;
            return text;
          },
          set_text};
}

}  // namespace

OptionRow MakeOptionRow(OptionType type, const std::string& key, const std::string& unit, double min, double max,
                        const std::vector<std::string>& choices, bool editable, const QString& tooltip,
                        const std::string& value) {
  OptionRow row;
  if (type == OptionType::kInteger || type == OptionType::kNumber) {
    row = NumberRow(type, unit, min, max, value);
  } else if (type == OptionType::kFlag) {
    auto* box = new QCheckBox;
    box->setChecked(value == "true");
    row = {box, [box] { return std::string(box->isChecked() ? "true" : "false"); },
           [box](const std::string& text) { box->setChecked(text == "true" || text == "1"); }};
  } else if (type == OptionType::kChoice) {
    row = ChoiceRow(choices, editable, value);
  } else if (type == OptionType::kText) {
    auto* line = new QLineEdit(QString::fromStdString(value));
    row = {line, [line] { return line->text().toStdString(); },
           [line](const std::string& text) { line->setText(QString::fromStdString(text)); }};
  } else {
    row = ChoiceListRow(choices, value);
  }
  row.widget->setObjectName(QString::fromStdString(key));
  row.widget->setToolTip(tooltip);
  return row;
}

void AddFormRow(QFormLayout* form, const QString& label, const QString& tooltip, QWidget* widget) {
  auto* text = new QLabel(label);
  text->setToolTip(tooltip);
  form->addRow(text, widget);
}

}  // namespace hexcal::ui
