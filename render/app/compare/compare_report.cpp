#include "render/app/compare/compare_report.h"

#include <set>
#include <system_error>

#include "render/app/compare/html_report.h"
#include "render/app/compare/summary_files.h"

namespace spume::compare {
namespace fs = std::filesystem;
namespace {

void remove_stale_images(const fs::path& dir, const std::vector<FrameResult>& results) {
  std::set<fs::path> written;
  for (const FrameResult& r : results)
    for (const std::string* rel : {&r.thumb_reference, &r.thumb_candidate, &r.thumb_heat, &r.diff_image, &r.heat_image})
      if (!rel->empty()) written.insert(dir / *rel);
  for (const char* sub : {"thumbs", "diff"}) {
    std::error_code ec;
    std::vector<fs::path> stale;
    for (fs::directory_iterator it(dir / sub, ec), end; !ec && it != end; it.increment(ec))
      if (it->path().extension() == ".png" && !written.count(it->path())) stale.push_back(it->path());
    for (const fs::path& p : stale) fs::remove(p, ec);
  }
}

}  // namespace

std::vector<FrameResult> compare_and_report(const FrameSet& set, const CompareOptions& options,
                                            const std::function<void(size_t)>& progress) {
  std::vector<FrameResult> results = compare_frames(set, options, progress);
  if (options.out) {
    const CompareReport report{set, results, options};
    write_summary_files(report, *options.out);
    write_report_html(report, *options.out);
    remove_stale_images(*options.out, results);
  }
  return results;
}

}  // namespace spume::compare
