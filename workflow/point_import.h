// A tracker's export added to a points session's points file (issue 38,
// docs/session.md, "Points sessions"): the GUI's Acquire step imports the
// points the tracker's software (SpatialAnalyzer's ASCII export, or CSV
// pose,point,x,y,z[,sigma]) wrote for one pose, or for several, and its sim
// tracker records the points it measured.
//
// A file of one point set is the pose the operator chose, whatever its group
// is called (SpatialAnalyzer names it Group1 unless told); a file of several
// sets keeps their names, which must then be the poses'. A set of a pose the
// points file has already replaces it, when asked to (`replace`). The points
// file is rewritten whole, atomically, under the session lock, in its own
// layout (SpatialAnalyzer's, or CSV when it is CSV); a point without its own
// σ stays without (the session's point_sigma applies), except in a CSV file
// whose σ column another point needs, where it is written as the session's σ.
//
//   StatusOr<PointImport> import = ReadPointImport("run1", "pose7.txt", "pose_0007");
//   if (import.ok() && import->replaced.empty()) WritePointImport("run1", *import);
#pragma once

#include <string>
#include <vector>

#include "core/point_file.h"
#include "core/status.h"

namespace hexcal::workflow {

struct PointImport {
  PointSets sets;                      // as they will be written: each named after its pose
  std::vector<std::string> replaced;  // poses of `sets` the session's points file has already
  std::string source;                  // the imported file's name, for messages
};

// The point sets of `file` (either layout), named as above: one set is
// `single_pose`'s (when not empty). Errors: not a points session, a file that
// does not load (named, with its line), a name a pose cannot have.
StatusOr<PointImport> ReadPointImport(const std::string& session_dir, const std::string& file,
                                      const std::string& single_pose);

// `import` merged into the session's points file (created when there is
// none): a pose it has already is replaced when `replace`, else refused
// naming it. Under the session lock, briefly waited for.
Status WritePointImport(const std::string& session_dir, const PointImport& import, bool replace);

}  // namespace hexcal::workflow
