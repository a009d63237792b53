#include "workflow/point_import.h"

#include <algorithm>
#include <filesystem>
#include <limits>
#include <set>
#include <sstream>

#include "core/atomic_file.h"
#include "core/csv.h"
#include "core/session.h"
#include "core/session_lock.h"
#include "session/session_models.h"

namespace hexcal::workflow {
namespace {

namespace fs = std::filesystem;

// The σ a point is read with when its line gives none: positive (the parser
// refuses others) and never a tracker's, so that it is written back as none.
constexpr double kNoOwnSigma = std::numeric_limits<double>::max();

bool HasOwnSigma(const NamedPoint& point) { return point.sigma != kNoOwnSigma; }

// A pose name is a field of either layout: no separator, quote or comment mark.
Status CheckPoseName(const std::string& pose, const std::string& where) {
  const bool bad = pose.empty() || pose.find_first_of(" \t\r\n,;\"'") != std::string::npos || pose[0] == '#' ||
                   pose.rfind("//", 0) == 0;
  if (bad) return Status::BadInput(where + ": '" + pose + "' cannot name a pose (no spaces, commas, quotes or #)");
  return Status::Ok();
}

struct SessionPointsFile {
  std::string path;
  double point_sigma = 0;
};

StatusOr<SessionPointsFile> PointsFileOf(const std::string& dir) {
  StatusOr<SessionConfig> config = LoadSessionConfig(dir);
  if (!config.ok()) return config.status();
  if (config->instrument != Instrument::kPoints)
    return Status::BadInput(dir + ": not a points session (session.yaml has no 'instrument: points')");
  // A points file not written yet is the session folder's, never one of the
  // working folder that ResolveSessionFile would fall back on.
  std::string path = ResolveSessionFile(dir, config->points);
  std::error_code error;
  if (!fs::exists(fs::symlink_status(path, error)) && fs::path(config->points).is_relative())
    path = (fs::path(dir) / config->points).string();
  return SessionPointsFile{path, config->point_sigma};
}

// As core/point_file.h decides: CSV when the first line that is not blank or a
// comment names the columns pose and point.
bool IsCsvLayout(const std::string& text) {
  std::istringstream lines(text.rfind("\xEF\xBB\xBF", 0) == 0 ? text.substr(3) : text);
  for (std::string line; std::getline(lines, line);) {
    for (char& c : line)
      if (c == ',' || c == '\t' || c == '\r') c = ' ';
    std::istringstream words(line);
    std::set<std::string> fields;
    for (std::string word; words >> word;) fields.insert(word);
    if (fields.empty() || fields.begin()->rfind("//", 0) == 0 || (*fields.begin())[0] == '#') continue;
    return fields.count("pose") && fields.count("point");
  }
  return false;
}

// The comment lines a SpatialAnalyzer file opens with, kept on a rewrite.
std::string LeadingComments(const std::string& text) {
  std::istringstream lines(text);
  std::string kept;
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("//", 0) != 0 && line.rfind("#", 0) != 0) break;
    kept += line + "\n";
  }
  return kept;
}

Status WriteSpatialAnalyzer(const std::string& path, const std::string& comments, const PointSets& sets) {
  std::string text = comments.empty() ? "// collection group target x y z [sigma] (hexcal: the group is the pose)\n"
                                      : comments;
  for (const PointSet& set : sets)
    for (const NamedPoint& point : set.points) {
      text += "tracker " + set.pose + " " + point.name;
      for (int k = 0; k < 3; ++k) text += " " + FormatNumber(point.position[k]);
      if (HasOwnSigma(point)) text += " " + FormatNumber(point.sigma);
      text += "\n";
    }
  return WriteFileAtomically(path, text);
}

Status WriteCsvPoints(const std::string& path, const PointSets& sets, double point_sigma) {
  bool sigma_column = false;
  for (const PointSet& set : sets)
    for (const NamedPoint& point : set.points) sigma_column = sigma_column || HasOwnSigma(point);
  std::vector<std::string> header = {"pose", "point", "x", "y", "z"};
  if (sigma_column) header.push_back("sigma");
  std::vector<std::vector<std::string>> rows;
  for (const PointSet& set : sets)
    for (const NamedPoint& point : set.points) {
      std::vector<std::string> row = {set.pose, point.name};
      for (int k = 0; k < 3; ++k) row.push_back(FormatNumber(point.position[k]));
      if (sigma_column) row.push_back(FormatNumber(HasOwnSigma(point) ? point.sigma : point_sigma));
      rows.push_back(std::move(row));
    }
  return WriteCsv(path, header, rows);
}

// The sets of the session's points file and its text; none when there is no
// file yet or it holds only comments (a session made before the tracker's
// first export).
StatusOr<PointSets> ExistingSets(const std::string& path, std::string* text) {
  text->clear();
  std::error_code error;
  if (!fs::exists(fs::symlink_status(path, error))) return PointSets{};
  StatusOr<std::string> read = ReadFileToString(path, kMaxTableBytes);
  if (!read.ok()) return read.status();
  *text = std::move(*read);
  std::istringstream lines(*text);
  bool any = false;
  for (std::string line; !any && std::getline(lines, line);) {
    const size_t first = line.find_first_not_of(" \t\r\xEF\xBB\xBF");
    any = first != std::string::npos && line.compare(first, 2, "//") != 0 && line[first] != '#';
  }
  if (!any) return PointSets{};
  return ParsePointFile(*text, path, kNoOwnSigma);
}

}  // namespace

StatusOr<PointImport> ReadPointImport(const std::string& dir, const std::string& file, const std::string& single_pose) {
  StatusOr<SessionPointsFile> session = PointsFileOf(dir);
  if (!session.ok()) return session.status();
  const std::string source = fs::path(file).filename().string();
  StatusOr<PointSets> sets = LoadPointFile(file, kNoOwnSigma, source);
  if (!sets.ok()) return sets.status();
  if (sets->empty()) return Status::BadInput(source + ": no points");
  if (sets->size() == 1 && !single_pose.empty()) sets->front().pose = single_pose;
  PointImport import{std::move(*sets), {}, source};
  for (const PointSet& set : import.sets)
    if (Status s = CheckPoseName(set.pose, source); !s.ok()) return s;
  std::string text;
  StatusOr<PointSets> existing = ExistingSets(session->path, &text);
  if (!existing.ok()) return existing.status();
  std::set<std::string> there;
  for (const PointSet& set : *existing) there.insert(set.pose);
  for (const PointSet& set : import.sets)
    if (there.count(set.pose)) import.replaced.push_back(set.pose);
  return import;
}

Status WritePointImport(const std::string& dir, const PointImport& import, bool replace) {
  StatusOr<SessionPointsFile> session = PointsFileOf(dir);
  if (!session.ok()) return session.status();
  StatusOr<SessionLock> lock = SessionLock::Acquire(dir, LockWait::kBriefly);
  if (!lock.ok()) return lock.status();
  // The file as it is now, under the lock: another writer's sets are kept.
  std::string text;
  StatusOr<PointSets> existing = ExistingSets(session->path, &text);
  if (!existing.ok()) return existing.status();
  PointSets merged = std::move(*existing);
  for (const PointSet& set : import.sets) {
    auto same = std::find_if(merged.begin(), merged.end(), [&](const PointSet& s) { return s.pose == set.pose; });
    if (same == merged.end()) {
      merged.push_back(set);
    } else if (replace) {
      *same = set;
    } else {
      return Status::BadInput(fs::path(session->path).filename().string() + " has points of pose '" + set.pose +
                           "' already: replace them, or import another pose");
    }
  }
  if (IsCsvLayout(text)) return WriteCsvPoints(session->path, merged, session->point_sigma);
  return WriteSpatialAnalyzer(session->path, LeadingComments(text), merged);
}

}  // namespace hexcal::workflow
