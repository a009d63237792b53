// hexcal target print --target T --out target.pdf|target.png [--dpi D] [--force] [--json]
// hexcal target check --target T [--json]
#include <cctype>
#include <filesystem>
#include <iostream>
#include <memory>

#include "app/commands/cli_common.h"
#include "app/commands/command_table.h"
#include "app/commands/option_flags.h"
#include "core/csv.h"
#include "vision/target.h"
#include "vision/target_print.h"

namespace hexcal::cli {
namespace {

struct TargetOptions {
  std::string target = kDefaultTargetName, out;
  std::shared_ptr<OptionEntries> print = std::make_shared<OptionEntries>();  // --dpi over TargetPrintOptions
  OptionFlagNames flags;
  bool force = false, json = false;
};

const char* LayoutName(TargetLayout layout) {
  switch (layout) {
    case TargetLayout::kGrid:
      return "grid";
    case TargetLayout::kIdMatrix:
      return "id_matrix";
    case TargetLayout::kTagList:
      break;
  }
  return "tag_list";
}

// The grid's keys always; null where the layout has no such thing, and
// `tags: [{id, x, y}]` for a layout that is not a plain grid.
nlohmann::json TargetJson(const Target& target) {
  const TargetLayout layout = target.Layout();
  const bool list = layout == TargetLayout::kTagList;
  const auto grid_only = [&](auto value) { return list ? nlohmann::json() : nlohmann::json(value); };
  nlohmann::json json = {
      {"family", target.family},
      {"layout", LayoutName(layout)},
      {"rows", grid_only(target.rows)},
      {"cols", grid_only(target.cols)},
      {"tag_size", target.tag_size},
      {"tag_spacing", grid_only(target.tag_spacing)},
      {"gap", grid_only(target.Gap())},
      {"first_id", layout == TargetLayout::kGrid ? nlohmann::json(target.first_id) : nlohmann::json()},
      {"num_tags", target.NumTags()},
      {"length_unit", LengthUnitName(target.length_unit)},
      {"margin", target.margin},
      {"border_bits", target.border_bits},
      {"width", target.Width()},
      {"height", target.Height()}};
  if (layout != TargetLayout::kGrid) {
    nlohmann::json tags = nlohmann::json::array();
    for (int index = 0; index < target.NumTags(); ++index) {
      const Eigen::Vector2d origin = target.TagOrigin(index);
      tags.push_back({{"id", target.TagId(index)}, {"x", origin.x()}, {"y", origin.y()}});
    }
    json["tags"] = tags;
  }
  return json;
}

int RunTargetCheck(const TargetOptions& options, std::ostream& out, std::ostream& err) {
  StatusOr<Target> target = LoadTarget(options.target);
  if (!target.ok()) return ReportError(err, "target check", target.status());
  if (options.json) {
    out << JsonText(nlohmann::json{{"ok", true}, {"target", TargetJson(*target)}});
  } else {
    out << "ok: " << DescribeTarget(*target) << "\n";
  }
  return kExitOk;
}

// As WriteTargetPrint decides it: by the extension, in any case.
bool IsPdfPath(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return extension == ".pdf";
}

int RunTargetPrint(const TargetOptions& options, std::ostream& out, std::ostream& err) {
  TargetPrintOptions print;
  if (Status s = ApplyOptionEntries(TargetPrintOptionSpecs(), *options.print, &print, "target print"); !s.ok())
    return ReportError(err, "target print", s);
  if (Status s = CheckOutputFree(options.out, options.force); !s.ok()) return ReportError(err, "target print", s);
  StatusOr<Target> target = LoadTarget(options.target);
  if (!target.ok()) return ReportError(err, "target print", target.status());
  if (Status s = WriteTargetPrint(*target, options.out, print.dpi); !s.ok()) {
    return ReportError(err, "target print", s, options.flags);
  }
  const std::vector<std::string> caption = TargetPrintCaption(*target);
  if (options.json) {
    nlohmann::json json = {{"out", options.out}, {"dpi", print.dpi}, {"target", TargetJson(*target)}};
    if (IsPdfPath(options.out)) json["sheet"] = DescribeSheet(TargetPdfSheet(*target));
    out << JsonText(json);
  } else {
    out << "target written to " << options.out << ": " << DescribeTarget(*target) << "\n";
    if (IsPdfPath(options.out)) out << "sheet: " << DescribeSheet(TargetPdfSheet(*target)) << "\n";
    out << caption[1] << "\n";
  }
  return kExitOk;
}

}  // namespace

void AddTargetCommand(CLI::App& app, int* exit_code) {
  CLI::App* target = app.add_subcommand("target", "check or print an AprilTag target (grid, id matrix or tag list)");
  target->require_subcommand(1);

  auto check = std::make_shared<TargetOptions>();
  CLI::App* check_sub = target->add_subcommand("check", "validate a target file and describe it");
  check_sub->add_option("--target", check->target, "target YAML file or the built-in name aprilgrid-6x6")
      ->capture_default_str();
  check_sub->add_flag("--json", check->json, "print one JSON object on stdout");
  check_sub->callback([=] { *exit_code = RunTargetCheck(*check, std::cout, std::cerr); });

  auto print = std::make_shared<TargetOptions>();
  CLI::App* print_sub = target->add_subcommand("print", "write a printable target at exact scale (PDF or PNG)");
  print_sub->add_option("--target", print->target, "target YAML file or the built-in name aprilgrid-6x6")
      ->capture_default_str();
  print_sub->add_option("--out", print->out, "output file, .pdf or .png")->required();
  AddOptionFlags(print_sub, TargetPrintOptionSpecs(), print->print, &print->flags);
  print_sub->add_flag("--force", print->force, "overwrite --out if it exists");
  print_sub->add_flag("--json", print->json, "print one JSON object on stdout");
  print_sub->callback([=] { *exit_code = RunTargetPrint(*print, std::cout, std::cerr); });
}

}  // namespace hexcal::cli
