#include "render/app/compare/frame_set.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <map>
#include <set>
#include <system_error>

#include "sim/core/frame_spec.h"
#include "sim/io/frame_pattern.h"

namespace spume::compare {
namespace fs = std::filesystem;
namespace {

enum class Kind { file, folder, pattern };

struct Side {
  const char* name;  // "REFERENCE" or "NEW"
  std::string text;  // as typed
  Kind kind = Kind::file;
};

Side classify(const char* name, const std::string& text) {
  std::error_code ec;
  if (text.empty()) throw UsageError(str(name, " is empty; give a PNG file, a folder of frames or a pattern such as frames/%04d.png"));
  if (fs::is_directory(text, ec)) return {name, text, Kind::folder};
  if (fs::exists(text, ec)) return {name, text, Kind::file};
  if (is_frame_pattern(text)) return {name, text, Kind::pattern};
  throw UsageError(str(name, " ", text, ": no such file or folder (give a PNG file, a folder of frames or a pattern "
                       "such as frames/%04d.png)"));
}

bool is_png_name(const std::string& name) {
  if (name.size() < 5) return false;
  std::string ext = name.substr(name.size() - 4);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext == ".png";
}

std::vector<std::string> png_names(const fs::path& folder) {
  std::vector<std::string> names;
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    std::error_code type_ec;
    if (is_png_name(name) && !it->is_directory(type_ec)) names.push_back(name);
  }
  if (ec) throw UsageError(str("cannot list folder ", folder.string(), ": ", ec.message()));
  return names;
}

// A folder with no PNG of its own but a frames/ subfolder (a scene's output folder) means the subfolder.
fs::path frames_folder(const Side& side, std::vector<std::string>* notes) {
  const fs::path folder(side.text);
  std::error_code ec;
  if (png_names(folder).empty() && fs::is_directory(folder / "frames", ec) && !png_names(folder / "frames").empty()) {
    notes->push_back(str(side.name, " ", side.text, " holds no PNG; comparing its frames/ folder"));
    return folder / "frames";
  }
  return folder;
}

// The trailing digits of a file's stem ("beauty.0012.png" -> 12), if any fit an int.
std::optional<int> trailing_number(const std::string& name) {
  const std::string stem = fs::path(name).stem().string();
  size_t start = stem.size();
  while (start > 0 && std::isdigit(static_cast<unsigned char>(stem[start - 1]))) --start;
  if (start == stem.size()) return std::nullopt;
  int value = 0;
  const auto [end, err] = std::from_chars(stem.data() + start, stem.data() + stem.size(), value);
  if (err != std::errc() || end != stem.data() + stem.size()) return std::nullopt;
  return value;
}

std::vector<int> pattern_frames(const Side& side, const std::string& pattern) {
  try {
    return find_pattern_frames(pattern);
  } catch (const Error& e) {
    throw UsageError(str(side.name, ": ", e.what()));
  }
}

std::vector<int> select_frames(const std::string& spec, int first, int last) {
  try {
    return parse_frame_spec(spec, first, last, "--frames");
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
}

std::string safe_stem(const std::string& label) {
  std::string s = fs::path(label).stem().string();
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.') c = '_';
  return s.empty() ? "frame" : s;
}

void assign_stems(std::vector<FramePair>* frames) {
  std::set<std::string> used;
  for (FramePair& f : *frames) {
    std::string stem = safe_stem(f.label);
    // Names that differ only in characters replaced above get a numeric suffix.
    for (int k = 2; used.count(stem); ++k) stem = safe_stem(f.label) + "_" + std::to_string(k);
    used.insert(stem);
    f.stem = stem;
  }
}

FrameSet resolve_files(const Side& ref, const Side& cand, const std::optional<std::string>& spec) {
  if (spec) throw UsageError("--frames selects numbered frames of folders or patterns; REFERENCE and NEW are two files");
  FrameSet set;
  set.mode = FrameSet::Mode::files;
  set.reference_source = ref.text, set.candidate_source = cand.text;
  FramePair pair;
  pair.label = fs::path(ref.text).filename().string();
  pair.reference = ref.text, pair.candidate = cand.text;
  pair.has_reference = pair.has_candidate = true;
  set.frames.push_back(pair);
  return set;
}

FrameSet resolve_folders(const Side& ref, const Side& cand, const std::optional<std::string>& spec) {
  FrameSet set;
  set.mode = FrameSet::Mode::folders;
  const fs::path rdir = frames_folder(ref, &set.notes), cdir = frames_folder(cand, &set.notes);
  set.reference_source = rdir.string(), set.candidate_source = cdir.string();
  std::map<std::string, std::pair<bool, bool>> names;  // name -> (in reference, in new)
  for (const auto& n : png_names(rdir)) names[n].first = true;
  for (const auto& n : png_names(cdir)) names[n].second = true;
  if (names.empty())
    throw UsageError(str("no PNG files in REFERENCE ", rdir.string(), " nor in NEW ", cdir.string()));
  std::optional<std::set<int>> selected;
  if (spec) {
    std::vector<int> numbers;
    for (const auto& [name, sides] : names)
      if (auto n = trailing_number(name)) numbers.push_back(*n);
    if (numbers.empty())
      throw UsageError(str("--frames: no file name in ", rdir.string(), " or ", cdir.string(), " ends in a frame number"));
    const auto [lo, hi] = std::minmax_element(numbers.begin(), numbers.end());
    const std::vector<int> chosen = select_frames(*spec, *lo, *hi);
    selected = std::set<int>(chosen.begin(), chosen.end());
  }
  for (const auto& [name, sides] : names) {
    FramePair pair;
    pair.label = name;
    pair.number = trailing_number(name);
    if (selected && (!pair.number || !selected->count(*pair.number))) continue;
    pair.reference = rdir / name, pair.candidate = cdir / name;
    pair.has_reference = sides.first, pair.has_candidate = sides.second;
    set.frames.push_back(pair);
  }
  if (set.frames.empty()) throw UsageError(str("--frames ", *spec, ": selects none of the PNG files found"));
  std::sort(set.frames.begin(), set.frames.end(),
            [](const FramePair& a, const FramePair& b) { return natural_less(a.label, b.label); });
  return set;
}

// A folder opposite a pattern takes the pattern's file name.
std::string as_pattern(const Side& side, const Side& other) {
  if (side.kind == Kind::pattern) return side.text;
  return (fs::path(side.text) / fs::path(other.text).filename()).string();
}

FrameSet resolve_patterns(const Side& ref, const Side& cand, const std::optional<std::string>& spec) {
  FrameSet set;
  set.mode = FrameSet::Mode::patterns;
  set.reference_source = as_pattern(ref, cand), set.candidate_source = as_pattern(cand, ref);
  const Side rp{ref.name, set.reference_source, Kind::pattern}, cp{cand.name, set.candidate_source, Kind::pattern};
  const std::vector<int> rf = pattern_frames(rp, rp.text), cf = pattern_frames(cp, cp.text);
  std::set<int> all(rf.begin(), rf.end());
  all.insert(cf.begin(), cf.end());
  if (all.empty())
    throw UsageError(str("no frames match REFERENCE ", rp.text, " nor NEW ", cp.text));
  std::vector<int> frames(all.begin(), all.end());
  if (spec) frames = select_frames(*spec, *all.begin(), *all.rbegin());
  const std::set<int> in_ref(rf.begin(), rf.end()), in_cand(cf.begin(), cf.end());
  for (int n : frames) {
    FramePair pair;
    pair.number = n;
    pair.reference = expand_frame_pattern(rp.text, n), pair.candidate = expand_frame_pattern(cp.text, n);
    pair.label = pair.reference.filename().string();
    pair.has_reference = in_ref.count(n) > 0, pair.has_candidate = in_cand.count(n) > 0;
    set.frames.push_back(pair);
  }
  return set;
}

}  // namespace

bool natural_less(const std::string& a, const std::string& b) {
  size_t i = 0, j = 0;
  auto digit = [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; };
  while (i < a.size() && j < b.size()) {
    if (digit(a[i]) && digit(b[j])) {
      size_t ie = i, je = j;
      while (ie < a.size() && digit(a[ie])) ++ie;
      while (je < b.size() && digit(b[je])) ++je;
      // Compare the runs as numbers without converting: strip leading zeros, then length, then digits.
      size_t is = i, js = j;
      while (is + 1 < ie && a[is] == '0') ++is;
      while (js + 1 < je && b[js] == '0') ++js;
      if (ie - is != je - js) return ie - is < je - js;
      if (int c = a.compare(is, ie - is, b, js, je - js); c != 0) return c < 0;
      if (ie - i != je - j) return ie - i < je - j;  // "7" before "007": fewer zeros first, for a total order
      i = ie, j = je;
    } else {
      if (a[i] != b[j]) return static_cast<unsigned char>(a[i]) < static_cast<unsigned char>(b[j]);
      ++i, ++j;
    }
  }
  return a.size() - i < b.size() - j;
}

namespace {

// Whether every frame on both sides is one file (a folder compared with itself, by two names).
bool same_files_on_both_sides(const FrameSet& set) {
  bool any = false;
  for (const FramePair& f : set.frames) {
    if (!f.has_reference || !f.has_candidate) return false;
    std::error_code ec;
    if (!fs::equivalent(f.reference, f.candidate, ec) || ec) return false;
    any = true;
  }
  return any;
}

}  // namespace

FrameSet resolve_frames(const std::string& reference, const std::string& candidate,
                        const std::optional<std::string>& frames_spec) {
  const Side ref = classify("REFERENCE", reference), cand = classify("NEW", candidate);
  FrameSet set;
  if (ref.kind == Kind::file && cand.kind == Kind::file) {
    set = resolve_files(ref, cand, frames_spec);
  } else if (ref.kind == Kind::file || cand.kind == Kind::file) {
    const Side& file = ref.kind == Kind::file ? ref : cand;
    const Side& other = ref.kind == Kind::file ? cand : ref;
    throw UsageError(str(file.name, " ", file.text, " is a file but ", other.name, " ", other.text, " is a ",
                         other.kind == Kind::folder ? "folder" : "frame pattern",
                         "; give two PNG files, or two folders or frame patterns"));
  } else if (ref.kind == Kind::folder && cand.kind == Kind::folder) {
    set = resolve_folders(ref, cand, frames_spec);
  } else {
    set = resolve_patterns(ref, cand, frames_spec);
  }
  assign_stems(&set.frames);
  if (same_files_on_both_sides(set))
    set.notes.push_back(str("warning: REFERENCE ", set.reference_source, " and NEW ", set.candidate_source,
                            " are the same files: every frame passes, and nothing new is compared"));
  return set;
}

}  // namespace spume::compare
