#include "core/working_set_design.h"

namespace hexcal {

CandidateRows GatherRows(const CandidateRows& all, const std::vector<int>& indices) {
  CandidateRows rows;
  rows.Resize(static_cast<int>(indices.size()));
  for (size_t k = 0; k < indices.size(); ++k) {
    for (int i = 0; i < kNumLegs; ++i) rows.legs[i].col(static_cast<int>(k)) = all.legs[i].col(indices[k]);
  }
  return rows;
}

std::vector<int> LargestOutside(const Eigen::ArrayXd& d, const std::vector<char>& member, int count, double above) {
  std::vector<int> outside;
  for (int j = 0; j < static_cast<int>(d.size()); ++j) {
    if (!member[j] && d[j] > above) outside.push_back(j);
  }
  const auto larger = [&](int a, int b) { return d[a] > d[b] || (d[a] == d[b] && a < b); };
  if (static_cast<int>(outside.size()) > count) {
    std::nth_element(outside.begin(), outside.begin() + count, outside.end(), larger);
    outside.resize(count);
  }
  std::sort(outside.begin(), outside.end(), larger);
  return outside;
}

}  // namespace hexcal
