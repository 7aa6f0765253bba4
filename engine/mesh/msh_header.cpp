#include "engine/mesh/msh_header.hpp"

#include <fstream>
#include <sstream>
#include <string>

namespace rockdd {

namespace {

/// At most 40 characters of `line`, control and non-ASCII bytes shown as '?', for messages.
std::string printable(const std::string& line) {
  std::string text = line.substr(0, 40);
  for (char& c : text)
    if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f) c = '?';
  return "\"" + text + (line.size() > 40 ? "...\"" : "\"");
}

/// `line` without trailing spaces, tabs and the '\r' of a file written on Windows.
std::string trimmed(std::string line) {
  const auto last = line.find_last_not_of(" \t\r");
  line.erase(last == std::string::npos ? 0 : last + 1);
  return line;
}

}  // namespace

// Both checks were found by fuzzing (tests/fuzz). Gmsh picks its reader by the first line, not
// by the .msh extension: any other file it reads as a .geo script, running its commands
// (SystemCall runs a shell command) and meshing whatever it draws. And a text file declared
// binary, or data sizes other than 8, make Gmsh's reader take counts from arbitrary bytes
// and allocate gigabytes for them.
void check_msh_header(const std::filesystem::path& file, const MeshSource& source) {
  std::ifstream in(file, std::ios::binary);
  std::string first, second;
  std::getline(in, first);
  std::getline(in, second);
  const std::string in_file = " (in " + file.string() + ")";
  if (trimmed(first) != "$MeshFormat")
    source.fail("expected a Gmsh .msh file whose first line is $MeshFormat, got " +
                (first.empty() && !in ? std::string("an empty file") : printable(first)) + in_file);
  std::istringstream fields(second);
  double version = 0.0;
  int file_type = -1, data_size = 0;
  fields >> version >> file_type >> data_size;
  const bool format_2 = version >= 2.0 && version < 3.0, format_41 = version == 4.1;
  if (!fields || !(format_2 || format_41) || (file_type != 0 && file_type != 1) || data_size != 8)
    source.fail(
        "expected the .msh header \"<version> <file-type> <data-size>\" with version 2.x or "
        "4.1, file-type 0 (ASCII) or 1 (binary) and data-size 8, got " +
        printable(second) + in_file);
  // The contents are checked before Gmsh reads them (msh2_node_references, msh4_contents);
  // the format-2 check reads ASCII files only.
  if (format_2 && file_type == 1)
    source.fail(
        "expected an ASCII format-2 .msh (file-type 0) or a format-4.1 one, ASCII or binary, "
        "got a binary format-2 file, which rockdd does not check before Gmsh reads it: save the "
        "mesh as ASCII or as format 4.1 (Gmsh: Mesh.MshFileVersion = 4.1)" +
        in_file);
}

}  // namespace rockdd
