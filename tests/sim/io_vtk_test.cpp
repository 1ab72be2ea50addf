#include <gtest/gtest.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>

#include "sim/core/error.h"
#include "tests/support/error_of.h"
#include "tests/support/files.h"
#include "tests/support/temp_dir.h"
#include "tests/sim/io_test_support.h"
#include "sim/io/attribute_names.h"
#include "sim/io/vtk.h"

namespace fs = std::filesystem;
using namespace spume;
using namespace spume::io_test;
using namespace spume::testing;

namespace {

template <typename T>
std::string le_bytes(std::initializer_list<T> values) {
  std::string out;
  for (T v : values) out.append(reinterpret_cast<const char*>(&v), sizeof(T));
  return out;
}

std::string base64(const std::string& in) {
  static const char* abc = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < in.size(); i += 3) {
    const size_t n = std::min<size_t>(3, in.size() - i);
    uint32_t bits = 0;
    for (size_t k = 0; k < 3; ++k) bits = bits << 8 | (k < n ? uint8_t(in[i + k]) : 0);
    for (size_t k = 0; k < 4; ++k) out += k <= n ? abc[(bits >> (18 - 6 * k)) & 63] : '=';
  }
  return out;
}

std::string zlib(const std::string& in) {
  uLongf len = compressBound(uLong(in.size()));
  std::string out(len, '\0');
  EXPECT_EQ(compress(reinterpret_cast<Bytef*>(out.data()), &len, reinterpret_cast<const Bytef*>(in.data()), uLong(in.size())),
            Z_OK);
  out.resize(len);
  return out;
}

// Three particles used by the XML tests.
const std::string kPoints = le_bytes<float>({0, 0, 0, 1, 2, 3, -1, 0.5f, 0.25f});
const std::string kVelocity = le_bytes<float>({1, 0, 0, 0, 1, 0, 0, 0, 1});
const std::string kIds = le_bytes<int32_t>({30, 20, 10});

void expect_three_particles(const FluidFrame& f) {
  ASSERT_EQ(f.size(), 3u);
  EXPECT_EQ(f.positions[1], Vec3f(1, 2, 3));
  EXPECT_EQ(f.positions[2], Vec3f(-1, 0.5f, 0.25f));
  EXPECT_EQ(f.velocities[1], Vec3f(0, 1, 0));
  EXPECT_EQ(f.ids, (std::vector<uint32_t>{30, 20, 10}));
}

std::string vtu(const std::string& root_attrs, const std::string& points, const std::string& arrays,
                const std::string& tail = "") {
  return "<?xml version=\"1.0\"?>\n<!-- comment <with> brackets -->\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" " +
         root_attrs + ">\n<UnstructuredGrid>\n<Piece NumberOfPoints=\"3\" NumberOfCells=\"0\">\n<Points>\n" + points +
         "</Points>\n<PointData>\n" + arrays + "</PointData>\n<Cells></Cells>\n</Piece>\n</UnstructuredGrid>\n" + tail +
         "</VTKFile>\n";
}

}  // namespace

TEST(Vtk, ReadsAsciiPolyData) {
  TempDir dir;
  const fs::path p = dir.write("a.vtk",
                               "# vtk DataFile Version 3.0\nhand written\nASCII\nDATASET POLYDATA\n"
                               "POINTS 3 float\n0 0 0 1 2 3\n-1 0.5 0.25\n"
                               "VERTICES 3 6\n1 0\n1 1\n1 2\n"
                               "POINT_DATA 3\nSCALARS id int 1\nLOOKUP_TABLE default\n30 20 10\n"
                               "VECTORS velocity float\n1 0 0 0 1 0 0 0 1\n"
                               "SCALARS density float\nLOOKUP_TABLE default\n1000 1001 999\n");
  std::vector<PointAttribute> attrs;
  expect_three_particles(read_vtk(p, &attrs));
  ASSERT_EQ(attrs.size(), 3u);
  EXPECT_EQ(attrs[2].name, "density");
}

// Every name of the one attribute table (io/attribute_names.h), in both VTK readers. Each file also
// holds the table's last velocity name first, with other values: the name the table prefers is read,
// wherever it lies in the file.
TEST(Vtk, BothReadersReadEveryNameOfTheAttributeTable) {
  TempDir dir;
  const auto velocity = io::attribute_names(io::AttributeRole::Velocity), id = io::attribute_names(io::AttributeRole::Id),
             mass = io::attribute_names(io::AttributeRole::Mass);
  const std::string decoy(velocity.back());
  for (size_t k = 0; k < std::max({velocity.size(), id.size(), mass.size()}); ++k) {
    const std::string v(velocity[k % velocity.size()]), i(id[k % id.size()]), m(mass[k % mass.size()]);
    SCOPED_TRACE(v + ", " + i + ", " + m);
    const std::string legacy = "# vtk DataFile Version 3.0\nnames\nASCII\nDATASET POLYDATA\nPOINTS 3 float\n"
                               "0 0 0 1 2 3 -1 0.5 0.25\nPOINT_DATA 3\n" +
                               (v == decoy ? "" : "VECTORS " + decoy + " float\n7 7 7 7 7 7 7 7 7\n") +
                               "SCALARS " + i + " int 1\nLOOKUP_TABLE default\n30 20 10\n"
                               "VECTORS " + v + " float\n1 0 0 0 1 0 0 0 1\n"
                               "SCALARS " + m + " float 1\nLOOKUP_TABLE default\n0.5 0.5 0.5\n";
    const FluidFrame a = read_vtk(dir.write("k" + std::to_string(k) + ".vtk", legacy));
    expect_three_particles(a);
    EXPECT_EQ(a.masses, (std::vector<float>(3, 0.5f)));
    auto array = [](const std::string& type, const std::string& name, int comps, const std::string& values) {
      return "<DataArray type=\"" + type + "\" Name=\"" + name + "\" NumberOfComponents=\"" + std::to_string(comps) +
             "\" format=\"ascii\">" + values + "</DataArray>\n";
    };
    const std::string xml = vtu("byte_order=\"LittleEndian\"",
                                "<DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">\n"
                                "0 0 0 1 2 3 -1 0.5 0.25\n</DataArray>\n",
                                (v == decoy ? "" : array("Float32", decoy, 3, "7 7 7 7 7 7 7 7 7")) +
                                    array("Int32", i, 1, "30 20 10") + array("Float32", v, 3, "1 0 0 0 1 0 0 0 1") +
                                    array("Float32", m, 1, "0.5 0.5 0.5"));
    const FluidFrame b = read_vtu(dir.write("k" + std::to_string(k) + ".vtu", xml));
    expect_three_particles(b);
    EXPECT_EQ(b.masses, (std::vector<float>(3, 0.5f)));
  }
}

TEST(Vtk, ReadsAsciiUnstructuredGridWithFieldDataAndVersion51Cells) {
  TempDir dir;
  const fs::path p = dir.write("b.vtk",
                               "# vtk DataFile Version 5.1\nx\nascii\nDATASET UNSTRUCTURED_GRID\n"
                               "FIELD FieldData 1\nTIME 1 1 double\n0.75\n"
                               "POINTS 3 double\n0 0 0 1 2 3 -1 0.5 0.25\n"
                               "CELLS 4 3\nOFFSETS vtktypeint64\n0 1 2 3\nCONNECTIVITY vtktypeint64\n0 1 2\n"
                               "CELL_TYPES 3\n1 1 1\n"
                               "CELL_DATA 3\nSCALARS cellid int\n0 1 2\n"
                               "POINT_DATA 3\nFIELD FieldData 2\n"
                               "Velocity 3 3 float\n1 0 0 0 1 0 0 0 1\nMETADATA\nINFORMATION 0\n\n"
                               "ID 1 3 unsigned_long\n30 20 10\n");
  const FluidFrame f = read_vtk(p);
  expect_three_particles(f);
  EXPECT_EQ(f.time, 0.75);
}

TEST(Vtk, ReadsSplishSplashStyleBinary) {
  // Layout of SPlisHSPlasH's ParticleExporter_VTK: POINTS, CELLS, CELL_TYPES, POINT_DATA with SCALARS id
  // unsigned_int and a named lookup table, then FIELD FieldData arrays. The first x is chosen so its
  // bytes are "\n\n\n\n" and the first id is 10 ('\n'), to catch readers that skip whitespace into data.
  TempDir dir;
  float first_x;
  std::memcpy(&first_x, "\n\n\n\n", 4);
  const float xs[3][3] = {{first_x, 0, 0}, {1, 2, 3}, {-1, 0.5f, 0.25f}};
  std::string s = "# vtk DataFile Version 4.1\nSPlisHSPlasH particle data\nBINARY\nDATASET UNSTRUCTURED_GRID\nPOINTS 3 float\n";
  for (const auto& x : xs)
    for (float c : x) be(s, c);
  s += "\nCELLS 3 6\n";
  for (uint32_t i = 0; i < 3; ++i) be(s, 1u), be(s, i);
  s += "\nCELL_TYPES 3\n";
  for (int i = 0; i < 3; ++i) be(s, 1);
  s += "\nPOINT_DATA 3\nSCALARS id unsigned_int 1\nLOOKUP_TABLE id_table\n";
  for (uint32_t id : {10u, 20u, 30u}) be(s, id);
  s += "\nFIELD FieldData 2\nvelocity 3 3 float\n";
  for (float v : {1, 0, 0, 0, 1, 0, 0, 0, 1}) be(s, float(v));
  s += "\ndensity 1 3 float\n";
  for (float v : {1000, 1001, 999}) be(s, float(v));
  s += "\n";
  const fs::path p = dir.write("ParticleData_Fluid_1.vtk", s);
  std::vector<PointAttribute> attrs;
  const FluidFrame f = read_vtk(p, &attrs);
  ASSERT_EQ(f.size(), 3u);
  EXPECT_EQ(f.positions[0].x(), first_x);
  EXPECT_EQ(f.positions[2], Vec3f(-1, 0.5f, 0.25f));
  EXPECT_EQ(f.velocities[2], Vec3f(0, 0, 1));
  EXPECT_EQ(f.ids, (std::vector<uint32_t>{10, 20, 30}));
  ASSERT_EQ(attrs.size(), 3u);
  EXPECT_EQ(attrs[1].name, "velocity");
  EXPECT_EQ(attrs[1].components, 3);

  // Every truncation names the file.
  for (size_t cut : {size_t(10), size_t(80), size_t(100), s.size() / 2, s.size() - 20, s.size() - 2}) {
    const fs::path t = dir.write("cut" + std::to_string(cut) + ".vtk", s.substr(0, cut));
    const std::string msg = error_of([&] { read_vtk(t); });
    EXPECT_NE(msg.find(t.string()), std::string::npos) << cut << ": " << msg;
  }
}

TEST(Vtk, BinaryRoundTrip) {
  TempDir dir;
  FluidFrame f;
  f.index = 12;
  f.time = 0.24;
  f.positions = {Vec3f(0.1f, 0.2f, 0.3f), Vec3f(10, -20, 30), Vec3f(0, 0, 0), Vec3f(1e-8f, 1e8f, -0.0f)};
  f.velocities = {Vec3f(1, 2, 3), Vec3f(0, 0, 0), Vec3f(-1, -2, -3), Vec3f(0.5f, 0.5f, 0.5f)};
  f.ids = {3, 2, 1, 4294967295u};
  f.masses = {1, 2, 3, 4};
  const fs::path p = dir.path / "rt.vtk";
  write_vtk(p, f);
  const std::string bytes = read_file(p);
  EXPECT_EQ(bytes.rfind("# vtk DataFile Version", 0), 0u);
  EXPECT_NE(bytes.find("\nBINARY\n"), std::string::npos);
  const FluidFrame g = read_vtk(p);
  EXPECT_EQ(g.positions, f.positions);
  EXPECT_EQ(g.velocities, f.velocities);
  EXPECT_EQ(g.ids, f.ids);
  EXPECT_EQ(g.masses, f.masses);
  EXPECT_EQ(g.time, 0.24);
  write_vtk(p, FluidFrame{});
  EXPECT_EQ(read_vtk(p).size(), 0u);
}

TEST(Vtk, RejectsBadFiles) {
  TempDir dir;
  auto msg = [&](const std::string& name, const std::string& text) {
    const fs::path p = dir.write(name, text);
    const std::string m = error_of([&] { read_vtk(p); });
    EXPECT_NE(m.find(p.string()), std::string::npos) << m;
    return m;
  };
  const std::string head = "# vtk DataFile Version 3.0\nt\nASCII\n";
  EXPECT_NE(msg("a.vtk", "hello\n").find("not a legacy VTK file"), std::string::npos);
  EXPECT_NE(msg("b.vtk", head + "DATASET STRUCTURED_POINTS\n").find("allowed POLYDATA or UNSTRUCTURED_GRID"), std::string::npos);
  EXPECT_NE(msg("c.vtk", head + "DATASET POLYDATA\nPOINTS 2 float\n0 0 0 1 1 1\nPOINT_DATA 3\n").find("must agree"),
            std::string::npos);
  EXPECT_NE(msg("d.vtk", head + "DATASET POLYDATA\nPOINTS 2 float\n0 0 0 1 1\n").find("truncated"), std::string::npos);
  EXPECT_NE(msg("e.vtk", head + "DATASET POLYDATA\nPOINTS 1 float\n0 0 0\nWIBBLE 3\n").find("'WIBBLE'"), std::string::npos);
  EXPECT_NE(msg("f.vtk", head + "DATASET POLYDATA\nPOINTS 1 half\n0 0 0\n").find("'half'"), std::string::npos);
  EXPECT_NE(msg("g.vtk", head + "DATASET POLYDATA\nPOINTS 2 float\n0 0 0 inf 1 1\n").find("particle 1"), std::string::npos);
  EXPECT_NE(msg("h.vtk", head + "DATASET POLYDATA\nPOINTS 2 float\n0 0 0 1 1 1\nPOINT_DATA 2\nSCALARS id int\n"
                                "LOOKUP_TABLE default\n-1 4\n")
                .find("id -1"),
            std::string::npos);
  EXPECT_NE(msg("i.vtk", head + "DATASET POLYDATA\nPOINTS 99999999999 float\n0 0 0\n").find("truncated"), std::string::npos);
  EXPECT_NE(msg("j.vtk", head + "DATASET POLYDATA\n").find("no POINTS"), std::string::npos);
}

TEST(VtkXml, ReadsAsciiArrays) {
  TempDir dir;
  const fs::path p = dir.write("a.vtu", vtu("byte_order=\"LittleEndian\"",
                                            "<DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">\n"
                                            "0 0 0 1 2 3 -1 0.5 0.25\n</DataArray>\n",
                                            "<DataArray type=\"Float64\" Name=\"v\" NumberOfComponents=\"3\" format='ascii'>"
                                            "1 0 0 0 1 0 0 0 1</DataArray>\n"
                                            "<DataArray type=\"Int64\" Name=\"id\" format=\"ascii\">30 20 10</DataArray>\n"
                                            "<DataArray type=\"Float32\" Name=\"pressure\" format=\"ascii\">1 2 3</DataArray>\n"));
  std::vector<PointAttribute> attrs;
  expect_three_particles(read_vtu(p, &attrs));
  ASSERT_EQ(attrs.size(), 3u);
  EXPECT_EQ(attrs[2].name, "pressure");
  EXPECT_EQ(attrs[0].type, "Float64");
}

TEST(VtkXml, ReadsBase64BinaryArrays) {
  TempDir dir;
  // UInt32 headers; the header and data encoded together (points) and separately as VTK does (ids).
  auto header32 = [](size_t n) { return le_bytes<uint32_t>({uint32_t(n)}); };
  const std::string points = base64(header32(kPoints.size()) + kPoints);
  const std::string vel = base64(header32(kVelocity.size()) + kVelocity);
  const std::string ids = base64(header32(kIds.size())) + base64(kIds);
  const fs::path p = dir.write(
      "b.vtu", vtu("byte_order=\"LittleEndian\" header_type=\"UInt32\"",
                   "<DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"binary\">\n  " + points + "\n</DataArray>\n",
                   "<DataArray type=\"Float32\" Name=\"velocity\" NumberOfComponents=\"3\" format=\"binary\">" + vel +
                       "</DataArray>\n<DataArray type=\"Int32\" Name=\"id\" format=\"binary\">" + ids + "</DataArray>\n"));
  expect_three_particles(read_vtu(p));

  // A byte too few in the declared size, and a truncated base64 text.
  const std::string short_points = base64(header32(kPoints.size() - 4) + kPoints.substr(0, kPoints.size() - 4));
  const fs::path q = dir.write("c.vtu", vtu("", "<DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"binary\">" +
                                                    short_points + "</DataArray>\n", ""));
  EXPECT_NE(error_of([&] { read_vtu(q); }).find("holds 32 bytes"), std::string::npos);
  const fs::path r = dir.write("d.vtu", vtu("", "<DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"binary\">" +
                                                    points.substr(0, 20) + "</DataArray>\n", ""));
  const std::string msg = error_of([&] { read_vtu(r); });
  EXPECT_NE(msg.find("truncated"), std::string::npos) << msg;
  EXPECT_NE(msg.find(r.string()), std::string::npos) << msg;
}

TEST(VtkXml, ReadsZlibCompressedArraysWithUInt64Headers) {
  TempDir dir;
  // VTK's blocked layout: [blocks, block size, last block size, compressed sizes...], then the blocks.
  // Points use 16-byte blocks (36 bytes: 16 + 16 + 4), the others one block.
  auto compressed = [](const std::string& data, size_t block) {
    std::vector<std::string> parts;
    for (size_t i = 0; i < data.size(); i += block) parts.push_back(zlib(data.substr(i, block)));
    std::string header = le_bytes<uint64_t>({parts.size(), block, data.size() % block});
    for (const auto& c : parts) header += le_bytes<uint64_t>({c.size()});
    std::string body;
    for (const auto& c : parts) body += c;
    return base64(header) + base64(body);
  };
  const fs::path p = dir.write(
      "z.vtu", vtu("byte_order=\"LittleEndian\" header_type=\"UInt64\" compressor=\"vtkZLibDataCompressor\"",
                   "<DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"binary\">" + compressed(kPoints, 16) +
                       "</DataArray>\n",
                   "<DataArray type=\"Float32\" Name=\"Velocity\" NumberOfComponents=\"3\" format=\"binary\">" +
                       compressed(kVelocity, 65536) + "</DataArray>\n<DataArray type=\"Int32\" Name=\"ids\" format=\"binary\">" +
                       compressed(kIds, 65536) + "</DataArray>\n"));
  expect_three_particles(read_vtu(p));

  const fs::path lz4 = dir.write("lz4.vtu", vtu("compressor=\"vtkLZ4DataCompressor\"", "", ""));
  EXPECT_NE(error_of([&] { read_vtu(lz4); }).find("re-export"), std::string::npos);
}

TEST(VtkXml, ReadsRawAppendedDataAndPolyDataPieces) {
  TempDir dir;
  auto header32 = [](size_t n) { return le_bytes<uint32_t>({uint32_t(n)}); };
  const std::string blob = header32(kPoints.size()) + kPoints + header32(kVelocity.size()) + kVelocity + header32(kIds.size()) + kIds;
  const std::string off_v = std::to_string(4 + kPoints.size()), off_id = std::to_string(8 + kPoints.size() + kVelocity.size());
  const fs::path p = dir.write(
      "app.vtu", vtu("byte_order=\"LittleEndian\"",
                     "<DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"appended\" offset=\"0\"/>\n",
                     "<DataArray type=\"Float32\" Name=\"velocity\" NumberOfComponents=\"3\" format=\"appended\" offset=\"" +
                         off_v + "\"/>\n<DataArray type=\"Int32\" Name=\"id\" format=\"appended\" offset=\"" + off_id + "\"/>\n",
                     "<AppendedData encoding=\"raw\">\n _" + blob + "\n</AppendedData>\n"));
  expect_three_particles(read_vtu(p));

  // Two PolyData pieces (2 + 1 points), big-endian ascii is unaffected by byte order.
  const fs::path q = dir.write(
      "two.vtp",
      "<VTKFile type=\"PolyData\" byte_order=\"BigEndian\"><PolyData>"
      "<Piece NumberOfPoints=\"2\"><Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">"
      "0 0 0 1 2 3</DataArray></Points><PointData><DataArray type=\"UInt32\" Name=\"id\" format=\"ascii\">30 20"
      "</DataArray></PointData><Verts/></Piece>"
      "<Piece NumberOfPoints=\"1\"><Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">"
      "-1 0.5 0.25</DataArray></Points><PointData><DataArray type=\"UInt32\" Name=\"id\" format=\"ascii\">10"
      "</DataArray></PointData></Piece></PolyData></VTKFile>");
  const FluidFrame f = read_vtu(q);
  ASSERT_EQ(f.size(), 3u);
  EXPECT_EQ(f.positions[2], Vec3f(-1, 0.5f, 0.25f));
  EXPECT_EQ(f.ids, (std::vector<uint32_t>{30, 20, 10}));
}

TEST(VtkXml, RejectsBadFiles) {
  TempDir dir;
  auto msg = [&](const std::string& name, const std::string& text) {
    const fs::path p = dir.write(name, text);
    const std::string m = error_of([&] { read_vtu(p); });
    EXPECT_NE(m.find(p.string()), std::string::npos) << m;
    return m;
  };
  const std::string pts = "<DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">0 0 0 1 2 3 -1 0.5 0.25</DataArray>";
  EXPECT_NE(msg("a.vtu", "not xml").find("not an XML VTK file"), std::string::npos);
  EXPECT_NE(msg("b.vtu", "<VTKFile type=\"ImageData\"></VTKFile>").find("ImageData"), std::string::npos);
  EXPECT_NE(msg("c.vtu", "<VTKFile type=\"UnstructuredGrid\"><Piece NumberOfPoints=\"3").find("malformed XML"), std::string::npos);
  EXPECT_NE(msg("d.vtu", vtu("", pts.substr(0, pts.size() - 16) + "</DataArray>", "")).find("truncated"), std::string::npos);
  EXPECT_NE(msg("e.vtu", vtu("", pts, "<DataArray type=\"Float32\" Name=\"v\" NumberOfComponents=\"3\" format=\"appended\" "
                                      "offset=\"0\"/>"))
                .find("no <AppendedData>"),
            std::string::npos);
  EXPECT_NE(msg("f.vtu", vtu("", pts, "<DataArray type=\"Float32\" Name=\"v\" NumberOfComponents=\"3\" format=\"binary\">"
                                      "AAAA!AAA</DataArray>"))
                .find("invalid base64"),
            std::string::npos);
  EXPECT_NE(msg("g.vtu", vtu("", "<DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">0 0 0 1 2 3 -1 0.5 nan"
                                 "</DataArray>",
                             ""))
                .find("particle 2"),
            std::string::npos);
  EXPECT_NE(msg("h.vtu", vtu("", pts, "<DataArray type=\"Float16\" Name=\"v\" NumberOfComponents=\"3\" format=\"ascii\">"
                                      "</DataArray>"))
                .find("Float16"),
            std::string::npos);
}
