// A folder published whole (issue 13, "results as one unit"): its files are
// written into a fresh folder beside the final one, which is then swapped in
// with one rename, renameat2(RENAME_EXCHANGE). A reader sees the old folder or
// the new one, never a mix; a writer killed at any point leaves the old one.
//
//   StatusOr<StagedFolder> staged = StagedFolder::Begin("run1/results");
//   WriteFileAtomically(staged->File("report.json"), json);
//   Status published = staged->Publish();  // run1/results is now the new folder
//
// The staging folder is PARENT/.NAME.new-XXXXXX. Begin removes such folders
// left by killed writers, so the caller must be the folder's only writer (hold
// the session lock, core/session_lock.h). A final folder that is a symlink is
// replaced by the real folder; the link's target is never written or removed.
// docs/session.md, "Results as one unit".
#pragma once

#include <string>

#include "core/status.h"

namespace hexcal {

class StagedFolder {
 public:
  static StatusOr<StagedFolder> Begin(const std::string& final_path);

  StagedFolder(StagedFolder&& other) noexcept;
  StagedFolder& operator=(StagedFolder&&) = delete;
  StagedFolder(const StagedFolder&) = delete;
  StagedFolder& operator=(const StagedFolder&) = delete;
  // Not published: the staging folder and what it holds are removed.
  ~StagedFolder();

  const std::string& Path() const { return staging_; }
  std::string File(const std::string& name) const;

  // Swaps the staging folder in as the final one and removes the old one.
  Status Publish();

 private:
  StagedFolder(std::string final_path, std::string staging) : final_(std::move(final_path)), staging_(std::move(staging)) {}
  std::string final_;
  std::string staging_;
  bool published_ = false;
};

}  // namespace hexcal
