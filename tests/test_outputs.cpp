// Output writers: atomic files, number text, VTU frames and PVD collections.
#include <gtest/gtest.h>
#include <unistd.h>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine/common/atomic_file.hpp"
#include "engine/common/number_format.hpp"
#include "engine/output/vtu_writer.hpp"

namespace rockdd {
namespace {

namespace fs = std::filesystem;

/// A fresh, empty folder per test, removed afterwards.
class OutputFolder : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("rockdd_test_outputs_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  /// Names of every entry in the folder, hidden ones included.
  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir_))
      names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }

  fs::path dir_;
};

std::string read_all(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// ---------------------------------------------------------------- number_format

TEST(FormatNumber, RandomDoublesRoundTripBitExactly) {
  // Random bit patterns cover every exponent, subnormals included; the text must
  // parse back (from_chars and strtod both) to the same 64 bits.
  std::mt19937_64 rng(12345);
  int checked = 0;
  while (checked < 100000) {
    const std::uint64_t bits = rng();
    double value;
    std::memcpy(&value, &bits, sizeof value);
    if (!std::isfinite(value)) continue;
    const std::string text = format_number(value);
    double parsed = 0.0;
    const auto result = std::from_chars(text.data(), text.data() + text.size(), parsed);
    ASSERT_EQ(result.ec, std::errc()) << text;
    ASSERT_EQ(result.ptr, text.data() + text.size()) << text;
    ASSERT_EQ(std::memcmp(&parsed, &value, sizeof value), 0) << text;
    const double by_strtod = std::strtod(text.c_str(), nullptr);
    ASSERT_EQ(std::memcmp(&by_strtod, &value, sizeof value), 0) << text;
    ++checked;
  }
}

TEST(FormatNumber, RandomUnitRangeValuesRoundTrip) {
  // Values like times and stresses (not bit patterns) round-trip too.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int i = 0; i < 100000; ++i) {
    const double value = unit(rng) * std::pow(10.0, (i % 40) - 20);
    EXPECT_EQ(std::strtod(format_number(value).c_str(), nullptr), value);
  }
}

TEST(FormatNumber, CommonValuesAreShortAndReadable) {
  EXPECT_EQ(format_number(0.0), "0");
  EXPECT_EQ(format_number(1.0), "1");
  EXPECT_EQ(format_number(-2.5), "-2.5");
  EXPECT_EQ(format_number(100.0), "100");
  EXPECT_EQ(format_number(123456789.0), "123456789");
  EXPECT_EQ(format_number(0.1), "0.1");
  EXPECT_EQ(format_number(0.001), "0.001");
  EXPECT_EQ(format_number(1e-7), "1e-07");
  EXPECT_EQ(format_number(1e10), "1e+10");  // to_chars takes the shorter of fixed and scientific
  EXPECT_EQ(format_number(1e100), "1e+100");
  EXPECT_EQ(format_number(0.1 + 0.2), "0.30000000000000004");  // shortest that is still exact
}

// ---------------------------------------------------------------- atomic files

TEST_F(OutputFolder, WriteFileAtomicallyLeavesOnlyTheFile) {
  const fs::path path = dir_ / "summary.json";
  write_file_atomically(path, "{\"status\": \"ok\"}\n");
  EXPECT_EQ(read_all(path), "{\"status\": \"ok\"}\n");
  EXPECT_EQ(entries(), std::vector<std::string>{"summary.json"});
}

TEST_F(OutputFolder, WriteFileAtomicallyReplacesAnExistingFile) {
  const fs::path path = dir_ / "a.csv";
  write_file_atomically(path, "a long first version\n");
  write_file_atomically(path, "short\n");
  EXPECT_EQ(read_all(path), "short\n");
  EXPECT_EQ(entries(), std::vector<std::string>{"a.csv"});
}

TEST_F(OutputFolder, BinaryContentIsKeptByteForByte) {
  std::string content;
  for (int i = 0; i < 256; ++i) content.push_back(static_cast<char>(i));
  write_file_atomically(dir_ / "bytes", content);
  EXPECT_EQ(read_all(dir_ / "bytes"), content);
}

TEST_F(OutputFolder, MissingFolderIsAnErrorNamingThePath) {
  const fs::path path = dir_ / "no_such_folder" / "history.csv";
  try {
    write_file_atomically(path, "x");
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
    EXPECT_NE(message.find(std::strerror(ENOENT)), std::string::npos) << message;
  }
  EXPECT_FALSE(fs::exists(dir_ / "no_such_folder"));  // the caller creates folders, not us
}

TEST_F(OutputFolder, FileAppearsOnlyOnCommit) {
  const fs::path path = dir_ / "history.csv";
  AtomicFile file(path);
  file.stream() << "step,time\n0,0\n";
  EXPECT_FALSE(fs::exists(path));
  // `.<name>.tmp.<pid>.<n>`: the count keeps two threads' writes of one file apart.
  const std::string temp = ".history.csv.tmp." + std::to_string(::getpid()) + ".";
  ASSERT_EQ(entries().size(), 1u);
  EXPECT_EQ(entries().front().rfind(temp, 0), 0u) << entries().front();
  file.commit();
  EXPECT_EQ(read_all(path), "step,time\n0,0\n");
  EXPECT_EQ(entries(), std::vector<std::string>{"history.csv"});
  EXPECT_THROW(file.commit(), std::runtime_error);
}

TEST_F(OutputFolder, UncommittedFileLeavesNothingAndKeepsTheOldVersion) {
  const fs::path path = dir_ / "history.csv";
  write_file_atomically(path, "complete\n");
  {
    AtomicFile file(path);
    file.stream() << "trunc";  // an interrupted run
  }
  EXPECT_EQ(read_all(path), "complete\n");
  EXPECT_EQ(entries(), std::vector<std::string>{"history.csv"});
}

TEST_F(OutputFolder, FailedRenameThrowsAndCleansUp) {
  // A non-empty folder where the file should go: rename(2) must refuse.
  const fs::path path = dir_ / "frame.vtu";
  fs::create_directories(path / "occupied");
  {
    AtomicFile file(path);
    file.stream() << "data";
    try {
      file.commit();
      FAIL() << "expected std::runtime_error";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(entries(), std::vector<std::string>{"frame.vtu"});
  EXPECT_TRUE(fs::is_directory(path));
}

// ---------------------------------------------------------------- VTU reader for the tests

/// One <DataArray> of a VTU file with its appended bytes.
struct ReadArray {
  std::string type, name;
  int components = 1;
  std::uint64_t offset = 0;
  std::string bytes;
  template <class T>
  std::vector<T> values() const {
    std::vector<T> out(bytes.size() / sizeof(T));
    std::memcpy(out.data(), bytes.data(), out.size() * sizeof(T));
    return out;
  }
};

/// A VTU file read back: header attributes and arrays by section ("PointData", "CellData",
/// "Points", "Cells"). Fails the test on any inconsistency of the appended layout.
struct ReadVtu {
  std::string header;
  std::uint64_t num_points = 0, num_cells = 0;
  std::map<std::string, std::vector<ReadArray>> sections;

  const ReadArray& array(const std::string& section, const std::string& name) const {
    for (const ReadArray& a : sections.at(section))
      if (a.name == name) return a;
    throw std::out_of_range("no array " + name + " in " + section);
  }
};

std::string attribute(const std::string& element, const std::string& name) {
  const std::regex pattern("\\s" + name + "=\"([^\"]*)\"");
  std::smatch match;
  return std::regex_search(element, match, pattern) ? match[1].str() : std::string("<absent>");
}

std::size_t type_size(const std::string& type) {
  if (type == "Float64") return 8;
  if (type == "Int32") return 4;
  if (type == "UInt8") return 1;
  ADD_FAILURE() << "unexpected DataArray type " << type;
  return 1;
}

ReadVtu read_vtu(const fs::path& path) {
  const std::string file = read_all(path);
  ReadVtu vtu;
  const std::string marker = "<AppendedData encoding=\"raw\">";
  const std::size_t appended = file.find(marker);
  if (appended == std::string::npos) {
    ADD_FAILURE() << "no raw AppendedData";
    return vtu;
  }
  vtu.header = file.substr(0, appended);
  const std::size_t underscore = file.find('_', appended + marker.size());
  // Only whitespace may lie between the AppendedData tag and the '_' marker.
  for (std::size_t i = appended + marker.size(); i < underscore; ++i)
    EXPECT_TRUE(std::isspace(static_cast<unsigned char>(file[i])));
  const std::size_t data = underscore + 1;

  std::smatch piece;
  EXPECT_TRUE(std::regex_search(vtu.header, piece, std::regex("<Piece[^>]*>")));
  vtu.num_points = std::stoull(attribute(piece.str(), "NumberOfPoints"));
  vtu.num_cells = std::stoull(attribute(piece.str(), "NumberOfCells"));

  // Each DataArray with the section it is in; blocks must tile the appended section exactly.
  const std::regex element("<(PointData|CellData|Points|Cells)>|<DataArray[^>]*/>");
  std::string section;
  std::map<std::uint64_t, std::uint64_t> block_sizes;
  for (auto it = std::sregex_iterator(vtu.header.begin(), vtu.header.end(), element);
       it != std::sregex_iterator(); ++it) {
    if ((*it)[1].matched) {
      section = (*it)[1].str();
      continue;
    }
    const std::string e = it->str();
    EXPECT_EQ(attribute(e, "format"), "appended") << e;
    ReadArray a;
    a.type = attribute(e, "type");
    a.name = attribute(e, "Name");
    const std::string components = attribute(e, "NumberOfComponents");
    a.components = components == "<absent>" ? 1 : std::stoi(components);
    a.offset = std::stoull(attribute(e, "offset"));
    std::uint64_t count = 0;
    EXPECT_LE(data + a.offset + sizeof count, file.size()) << e;
    std::memcpy(&count, file.data() + data + a.offset, sizeof count);
    EXPECT_LE(data + a.offset + sizeof count + count, file.size()) << e;
    a.bytes = file.substr(data + a.offset + sizeof count, count);
    // The byte count must agree with the entity count the array belongs to.
    const std::uint64_t entities =
        section == "PointData" || section == "Points" ? vtu.num_points : vtu.num_cells;
    const std::uint64_t per_entity =
        section == "Cells" && a.name == "connectivity" ? 3 : a.components;
    EXPECT_EQ(count, entities * per_entity * type_size(a.type)) << e;
    block_sizes[a.offset] = sizeof count + count;
    vtu.sections[section].push_back(a);
  }
  std::uint64_t end = 0;
  for (const auto& [offset, size] : block_sizes) {
    EXPECT_EQ(offset, end) << "appended blocks must follow each other without gaps or overlap";
    end = offset + size;
  }
  EXPECT_EQ(file.substr(data + end), "\n  </AppendedData>\n</VTKFile>\n");
  return vtu;
}

// ---------------------------------------------------------------- VTU writer

TEST_F(OutputFolder, VtuHeaderDeclaresRawLittleEndianUInt64Appended) {
  const std::vector<double> xy = {0, 0, 1, 0, 0, 1};
  const std::vector<std::int32_t> tri = {0, 1, 2};
  write_vtu(dir_ / "one.vtu", xy, tri, {}, {});
  const ReadVtu vtu = read_vtu(dir_ / "one.vtu");
  std::smatch root;
  ASSERT_TRUE(std::regex_search(vtu.header, root, std::regex("<VTKFile[^>]*>")));
  EXPECT_EQ(attribute(root.str(), "type"), "UnstructuredGrid");
  EXPECT_EQ(attribute(root.str(), "byte_order"), "LittleEndian");
  EXPECT_EQ(attribute(root.str(), "header_type"), "UInt64");
  EXPECT_EQ(vtu.header.rfind("<?xml version=\"1.0\"?>\n", 0), 0u);
  EXPECT_EQ(vtu.num_points, 3u);
  EXPECT_EQ(vtu.num_cells, 1u);
  EXPECT_EQ(entries(), std::vector<std::string>{"one.vtu"});
}

TEST_F(OutputFolder, VtuValuesReadBackExactly) {
  // Two triangles on a unit square; 4 points, 2 cells.
  const std::vector<double> xy = {0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0 / 3.0};
  const std::vector<std::int32_t> tri = {0, 1, 2, 0, 2, 3};
  const std::vector<double> displacement = {0.1, -0.2, 0, 1e-300, 2.5,   0,
                                            -7,  3.25, 0, 0.5,    0.125, 0};
  const std::vector<double> stress = {1e6, -2e6, 3.5e5, -4e7, 5e-3, 6.0};
  const std::vector<double> damage = {0.0, 0.75};
  const std::vector<std::int32_t> block = {3, -1};
  write_vtu(dir_ / "frame_00010.vtu", xy, tri, {{"displacement", 3, displacement, {}}},
            {{"stress", 3, stress, {}}, {"damage", 1, damage, {}}, {"block", 1, {}, block}});
  const ReadVtu vtu = read_vtu(dir_ / "frame_00010.vtu");
  ASSERT_EQ(vtu.num_points, 4u);
  ASSERT_EQ(vtu.num_cells, 2u);

  const ReadArray& points = vtu.sections.at("Points").at(0);
  EXPECT_EQ(points.type, "Float64");
  EXPECT_EQ(points.components, 3);
  const std::vector<double> p = points.values<double>();
  ASSERT_EQ(p.size(), 12u);
  for (int n = 0; n < 4; ++n) {
    EXPECT_EQ(p[3 * n], xy[2 * n]);
    EXPECT_EQ(p[3 * n + 1], xy[2 * n + 1]);
    EXPECT_EQ(p[3 * n + 2], 0.0);
  }
  const ReadArray& connectivity = vtu.array("Cells", "connectivity");
  EXPECT_EQ(connectivity.type, "Int32");
  EXPECT_EQ(connectivity.values<std::int32_t>(), tri);
  const ReadArray& offsets = vtu.array("Cells", "offsets");
  EXPECT_EQ(offsets.type, "Int32");
  EXPECT_EQ(offsets.values<std::int32_t>(), (std::vector<std::int32_t>{3, 6}));
  const ReadArray& types = vtu.array("Cells", "types");
  EXPECT_EQ(types.type, "UInt8");
  EXPECT_EQ(types.values<std::uint8_t>(), (std::vector<std::uint8_t>{5, 5}));  // VTK_TRIANGLE

  const ReadArray& u = vtu.array("PointData", "displacement");
  EXPECT_EQ(u.type, "Float64");
  EXPECT_EQ(u.components, 3);
  EXPECT_EQ(u.values<double>(), displacement);
  const ReadArray& s = vtu.array("CellData", "stress");
  EXPECT_EQ(s.components, 3);
  EXPECT_EQ(s.values<double>(), stress);
  EXPECT_EQ(vtu.array("CellData", "damage").values<double>(), damage);
  const ReadArray& b = vtu.array("CellData", "block");
  EXPECT_EQ(b.type, "Int32");
  EXPECT_EQ(b.components, 1);
  EXPECT_EQ(b.values<std::int32_t>(), block);
}

TEST_F(OutputFolder, VtuOfALargerMeshKeepsItsLayout) {
  // A 30x20 grid split into triangles: offsets grow as 3, 6, 9, ... and every block lines up.
  const int nx = 30, ny = 20;
  std::vector<double> xy;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      xy.push_back(0.01 * i);
      xy.push_back(0.02 * j);
    }
  std::vector<std::int32_t> tri;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const std::int32_t a = j * (nx + 1) + i, b = a + 1, c = a + nx + 2, d = a + nx + 1;
      tri.insert(tri.end(), {a, b, c, a, c, d});
    }
  const std::size_t cells = tri.size() / 3;
  std::vector<double> principal(2 * cells);
  for (std::size_t i = 0; i < principal.size(); ++i) principal[i] = std::sin(0.1 * i);
  write_vtu(dir_ / "grid.vtu", xy, tri, {}, {{"principal", 2, principal, {}}});
  const ReadVtu vtu = read_vtu(dir_ / "grid.vtu");
  EXPECT_EQ(vtu.num_points, xy.size() / 2);
  EXPECT_EQ(vtu.num_cells, cells);
  const std::vector<std::int32_t> offsets = vtu.array("Cells", "offsets").values<std::int32_t>();
  ASSERT_EQ(offsets.size(), cells);
  for (std::size_t c = 0; c < cells; ++c)
    EXPECT_EQ(offsets[c], static_cast<std::int32_t>(3 * (c + 1)));
  EXPECT_EQ(vtu.array("Cells", "connectivity").values<std::int32_t>(), tri);
  EXPECT_EQ(vtu.array("CellData", "principal").values<double>(), principal);
}

TEST_F(OutputFolder, VtuRejectsInconsistentInput) {
  const std::vector<double> xy = {0, 0, 1, 0, 0, 1};
  const std::vector<std::int32_t> tri = {0, 1, 2};
  const std::vector<double> two = {1, 2};
  const std::vector<std::int32_t> bad_tri = {0, 1, 3};
  EXPECT_THROW(write_vtu(dir_ / "a.vtu", xy, tri, {{"u", 1, two, {}}}, {}), std::invalid_argument);
  EXPECT_THROW(write_vtu(dir_ / "a.vtu", xy, tri, {}, {{"s", 3, two, {}}}), std::invalid_argument);
  EXPECT_THROW(write_vtu(dir_ / "a.vtu", xy, bad_tri, {}, {}), std::invalid_argument);
  EXPECT_THROW(write_vtu(dir_ / "a.vtu", std::vector<double>{0, 0, 1}, {}, {}, {}),
               std::invalid_argument);
  EXPECT_TRUE(entries().empty());
}

// ---------------------------------------------------------------- PVD writer

TEST_F(OutputFolder, PvdListsEveryFrameWithItsExactTime) {
  const std::vector<std::pair<double, std::string>> frames = {
      {0.0, "frames/frame_00000.vtu"},
      {1e-4 / 3.0, "frames/frame_00100.vtu"},
      {0.1, "frames/a&b.vtu"}};
  write_pvd(dir_ / "frames.pvd", frames);
  const std::string text = read_all(dir_ / "frames.pvd");
  EXPECT_NE(text.find("<VTKFile type=\"Collection\""), std::string::npos);
  EXPECT_NE(text.find("<Collection>"), std::string::npos);
  EXPECT_NE(text.find("</VTKFile>"), std::string::npos);
  const std::regex dataset("<DataSet[^>]*/>");
  std::vector<std::pair<double, std::string>> read;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), dataset);
       it != std::sregex_iterator(); ++it)
    read.emplace_back(std::strtod(attribute(it->str(), "timestep").c_str(), nullptr),
                      attribute(it->str(), "file"));
  ASSERT_EQ(read.size(), 3u);
  EXPECT_EQ(read[0], frames[0]);
  EXPECT_EQ(read[1], frames[1]);
  EXPECT_EQ(read[2].first, 0.1);
  EXPECT_EQ(read[2].second, "frames/a&amp;b.vtu");  // escaped for XML
  EXPECT_EQ(entries(), std::vector<std::string>{"frames.pvd"});
}

}  // namespace
}  // namespace rockdd
