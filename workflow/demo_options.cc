#include "workflow/demo_options.h"

#include <string>

namespace hexcal::workflow {

const OptionTable<DemoRequest>& DemoOptions() {
  static const OptionTable<DemoRequest> table = [] {
    using Request = DemoRequest;
    OptionTable<Request> t;
    // Each pose is a rendered image (~0.4 MB) and a row of every table: the
    // bounds keep a typo (--poses 100000: 38 GB) from filling the disk.
    t.push_back(NumberOption<Request>("poses", "Poses", OptionType::kInteger, "poses", 8, 500,
                                      "planned calibration poses, each a rendered image",
                                      [](Request& r) -> int& { return r.poses; }));
    t.push_back(NumberOption<Request>("holdout", "Held-out poses", OptionType::kInteger, "poses", 0, 500,
                                      "random poses kept out to validate, each a rendered image (0: none)",
                                      [](Request& r) -> int& { return r.holdout; }));
    t.push_back(NumberOption<Request>(
        "random_poses", "Random poses", OptionType::kFlag, "", 0, 1,
        "record `poses` random feasible poses the camera sees instead of an IOOPS plan (for hexcal study)",
        [](Request& r) -> bool& { return r.random_poses; }));
    t.push_back(NumberOption<Request>("focal_error", "Focal error", OptionType::kNumber, "percent", -20, 20,
                                      "give the calibration a camera file whose focal length is off by this much; "
                                      "the images keep the true one",
                                      [](Request& r) -> double& { return r.focal_error_percent; }));
    t.push_back(ChoiceOption<Request>(
        "instrument", "Instrument", OptionType::kChoice,
        {InstrumentName(Instrument::kCamera), InstrumentName(Instrument::kPoints)},
        "what measures the poses: camera (rendered images of the board) or points (a laser tracker's 4 reflectors)",
        [](const Request& r) { return std::string(InstrumentName(r.instrument)); },
        [](Request& r, const std::string& v) {
          r.instrument = v == InstrumentName(Instrument::kPoints) ? Instrument::kPoints : Instrument::kCamera;
        }));
    t.push_back(NumberOption<Request>("point_sigma", "Point sigma", OptionType::kNumber, "mm", 0.0001, 1,
                                      "with the points instrument: the tracker's sigma on each coordinate",
                                      [](Request& r) -> double& { return r.point_sigma_mm; }));
    t.push_back(SeedOption<Request>("seed of the truth, the candidates and the noise",
                                    [](Request& r) -> uint64_t& { return r.seed; }));
    return t;
  }();
  return table;
}

Status DemoRequest::Check() const { return CheckOptionRanges(DemoOptions(), *this); }

}  // namespace hexcal::workflow
