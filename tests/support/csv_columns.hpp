#pragma once
// Reading a CSV file of numbers (history.csv, profiles) by column.
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace rockdd::test {

/// A CSV file's columns of numbers, by the names in its header line.
using CsvColumns = std::map<std::string, std::vector<double>>;

/// A CSV file as named columns of numbers.
inline CsvColumns read_csv(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> names;
  std::stringstream header(line);
  for (std::string cell; std::getline(header, cell, ',');) names.push_back(cell);
  CsvColumns columns;
  while (std::getline(in, line)) {
    std::stringstream row(line);
    std::size_t i = 0;
    for (std::string cell; std::getline(row, cell, ',') && i < names.size(); ++i)
      columns[names[i]].push_back(std::stod(cell));
  }
  return columns;
}

}  // namespace rockdd::test
