#include "sim/io/houdini_values.h"

#include <new>
#include <numeric>
#include <optional>

#include "sim/core/error.h"

namespace spume::hjson {
namespace {

// A run of numbers: a uniform array read in place, or a plain array parsed into doubles.
struct Numbers {
  const Reader* reader = nullptr;
  Token uniform;
  bool is_uniform = false;
  std::vector<double> plain;

  uint64_t size() const { return is_uniform ? uniform.count : plain.size(); }
  double operator[](uint64_t i) const { return is_uniform ? reader->element(uniform, i) : plain[size_t(i)]; }
};

Numbers read_numbers(Reader& r, std::string_view what) {
  Numbers n;
  n.reader = &r;
  const Token t = r.next();
  if (t.kind == Kind::UniformArray) {
    n.uniform = t;
    n.is_uniform = true;
    return n;
  }
  if (t.kind != Kind::ArrayBegin) r.fail_at(t.offset, what, " must be an array of numbers");
  while (!r.end_of(Kind::ArrayEnd)) {
    const Token v = r.next();
    if (v.kind == Kind::Number) n.plain.push_back(v.number);
    else if (v.kind == Kind::Bool) n.plain.push_back(v.boolean ? 1.0 : 0.0);
    else r.fail_at(v.offset, what, " must hold only numbers");
  }
  return n;
}

// Where each value of the block starts; read once all keys are known, since their order is free.
struct Block {
  std::optional<size_t> tuples, arrays, raw, packing, flags;
  std::optional<int64_t> pagesize, size;
};

// Constant pages let a few numbers stand for many elements: a count that does not fit is an Error naming
// the file, not an exception without one.
void allocate(const Reader& r, std::vector<double>& out, uint64_t count, int size, std::string_view what) {
  try {
    out.assign(size_t(count) * size_t(size), 0.0);
  } catch (const std::bad_alloc&) {
    fail(r.where(), ": ", what, ": ", count, " elements of ", size, " numbers do not fit in memory");
  }
}

void decode_paged(Reader& r, const Block& b, uint64_t count, int size, std::vector<double>& out, std::string_view what) {
  if (!b.pagesize) r.fail_at(*b.raw, what, ": paged values (rawpagedata) without a pagesize");
  const uint64_t pagesize = uint64_t(*b.pagesize);
  const uint64_t pages = count / pagesize + (count % pagesize != 0);
  std::vector<int> packing{size};
  if (b.packing) {
    r.seek(*b.packing);
    const Numbers p = read_numbers(r, str(what, " packing"));
    packing.clear();
    for (uint64_t i = 0; i < p.size(); ++i) {
      if (!(p[i] >= 1 && p[i] <= size)) r.fail_at(*b.packing, what, ": packing part ", p[i], "; allowed 1 to ", size);
      packing.push_back(int(p[i]));
    }
    if (std::accumulate(packing.begin(), packing.end(), 0) != size)
      r.fail_at(*b.packing, what, ": packing parts add up to ", std::accumulate(packing.begin(), packing.end(), 0),
                ", not the tuple size ", size);
  }
  // constant[part][page]; an absent or empty list means no constant page for that part.
  std::vector<std::vector<bool>> constant(packing.size());
  if (b.flags) {
    r.seek(*b.flags);
    r.expect(Kind::ArrayBegin, str(what, " constantpageflags"));
    size_t part = 0;
    while (!r.end_of(Kind::ArrayEnd)) {
      const size_t at = r.offset();
      if (part == packing.size())
        r.fail_at(at, what, ": constantpageflags has more lists than the ", packing.size(), " packed parts");
      const Numbers f = read_numbers(r, str(what, " constantpageflags"));
      if (f.size() != 0 && f.size() != pages)
        r.fail_at(at, what, ": constantpageflags lists ", f.size(), " pages; ", count, " elements in pages of ",
                  pagesize, " make ", pages);
      for (uint64_t i = 0; i < f.size(); ++i) constant[part].push_back(f[i] != 0.0);
      ++part;
    }
  }
  r.seek(*b.raw);
  const Numbers raw = read_numbers(r, str(what, " rawpagedata"));
  // Every page needs at least one number per part: a bound on the page count before walking the pages.
  if (raw.size() / packing.size() < pages)
    r.fail_at(*b.raw, what, ": rawpagedata holds ", raw.size(), " numbers, fewer than the ", pages, " pages of ",
              pagesize, " that ", count, " elements fill need");
  // What the layout needs, counted before anything is written.
  uint64_t needed = 0;
  for (uint64_t page = 0; page < pages; ++page) {
    const uint64_t elements = std::min(pagesize, count - page * pagesize);
    for (size_t k = 0; k < packing.size(); ++k)
      needed += uint64_t(packing[k]) * (!constant[k].empty() && constant[k][page] ? 1 : elements);
  }
  if (raw.size() != needed)
    r.fail_at(*b.raw, what, ": rawpagedata holds ", raw.size(), " numbers; ", count, " elements of ", size,
              " in pages of ", pagesize, " with the constant pages given need ", needed);
  allocate(r, out, count, size, what);
  uint64_t pos = 0;
  for (uint64_t page = 0; page < pages; ++page) {
    const uint64_t first = page * pagesize, elements = std::min(pagesize, count - first);
    int offset = 0;
    for (size_t k = 0; k < packing.size(); ++k) {
      const int width = packing[k];
      const bool is_constant = !constant[k].empty() && constant[k][page];
      for (uint64_t e = 0; e < elements; ++e)
        for (int c = 0; c < width; ++c)
          out[size_t((first + e) * uint64_t(size) + uint64_t(offset + c))] = raw[pos + (is_constant ? 0 : e * width) + c];
      pos += uint64_t(width) * (is_constant ? 1 : elements);
      offset += width;
    }
  }
}

}  // namespace

void read_values(Reader& r, uint64_t count, int size, std::vector<double>& out, std::string_view what) {
  const size_t start = r.offset();
  Block b;
  r.expect(Kind::ArrayBegin, str(what, " values"));
  while (!r.end_of(Kind::ArrayEnd)) {
    const std::string_view key = r.string(str(what, " value key"));
    if (key == "size") b.size = r.integer(str(what, " size"), 1, 1 << 16);
    else if (key == "pagesize") b.pagesize = r.integer(str(what, " pagesize"), 1, 1 << 16);  // Houdini's is 1024
    else {
      std::optional<size_t>* slot = key == "tuples" ? &b.tuples : key == "arrays" ? &b.arrays : key == "rawpagedata" ? &b.raw
                                    : key == "packing" ? &b.packing : key == "constantpageflags" ? &b.flags : nullptr;
      if (slot) *slot = r.offset();
      r.skip_value();  // "storage" and anything else: the numbers say their own storage
    }
  }
  const size_t end = r.offset();
  if (b.size && *b.size != size) r.fail_at(start, what, ": values have tuple size ", *b.size, ", the attribute ", size);
  if (b.raw) {
    decode_paged(r, b, count, size, out, what);
  } else if (b.tuples) {
    r.seek(*b.tuples);
    r.expect(Kind::ArrayBegin, str(what, " tuples"));
    out.clear();
    out.reserve(size_t(std::min<uint64_t>(count, 1 << 20)) * size_t(size));
    while (!r.end_of(Kind::ArrayEnd)) {
      const size_t at = r.offset();
      const Numbers t = read_numbers(r, str(what, " tuple"));
      if (t.size() != uint64_t(size)) r.fail_at(at, what, ": a tuple of ", t.size(), " numbers; the attribute has ", size);
      if (out.size() / size_t(size) == count) r.fail_at(at, what, ": more than ", count, " tuples");
      for (uint64_t c = 0; c < t.size(); ++c) out.push_back(t[c]);
    }
    if (out.size() != size_t(count) * size_t(size))
      r.fail_at(*b.tuples, what, ": ", out.size() / size_t(size), " tuples; the geometry has ", count, " elements");
  } else if (b.arrays) {
    r.seek(*b.arrays);
    r.expect(Kind::ArrayBegin, str(what, " arrays"));
    std::vector<Numbers> parts;
    while (!r.end_of(Kind::ArrayEnd)) {
      const size_t at = r.offset();
      parts.push_back(read_numbers(r, str(what, " arrays")));
      if (parts.back().size() != count)
        r.fail_at(at, what, ": an array of ", parts.back().size(), " numbers; the geometry has ", count, " elements");
    }
    if (parts.size() != size_t(size)) r.fail_at(*b.arrays, what, ": ", parts.size(), " arrays for a tuple size of ", size);
    allocate(r, out, count, size, what);
    for (int c = 0; c < size; ++c)
      for (uint64_t e = 0; e < count; ++e) out[size_t(e) * size_t(size) + size_t(c)] = parts[size_t(c)][e];
  } else {
    r.fail_at(start, what, ": values without rawpagedata, tuples or arrays");
  }
  r.seek(end);
}

}  // namespace spume::hjson

namespace spume::hjson {
std::vector<double> read_number_list(Reader& r, std::string_view what) {
  const Numbers n = read_numbers(r, what);
  std::vector<double> out;
  for (uint64_t i = 0; i < n.size(); ++i) out.push_back(n[i]);
  return out;
}
}  // namespace spume::hjson
