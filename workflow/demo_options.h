// The options of `hexcal demo` (workflow/demo.h): how many poses, held out
// or not, random or planned, the camera file's focal error, the instrument
// and its noise, the seed — each described once in DemoOptions()
// (core/option_spec.h). That table makes the `hexcal demo` flags and the
// table in docs/cli.md, and DemoRequest::Check checks a request against it.
//
//   DemoRequest request;  // 24 planned poses, 8 held out, a camera
//   Status s = ApplyOptionEntries(DemoOptions(), {{"poses", "64"}, {"holdout", "0"}}, &request, "demo");
#pragma once

#include "core/option_spec.h"
#include "workflow/demo.h"

namespace hexcal::workflow {

// The robot, the folder (--out, --force), the calibration's kind
// (--from-pixels or --two-stage, a pair of flags) and --json are not in it.
const OptionTable<DemoRequest>& DemoOptions();

}  // namespace hexcal::workflow
