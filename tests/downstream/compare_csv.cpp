// compare_csv A.csv B.csv REL_TOL: exit 0 when both files have the same header
// and the same number of rows, and every value of a column agrees within
// REL_TOL times the largest magnitude of that column in A; otherwise prints
// the first difference and exits 1.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace {

struct Table {
  std::string header;
  std::vector<std::vector<double>> rows;
};

bool read(const char* path, Table& table) {
  std::ifstream in(path);
  if (!in || !std::getline(in, table.header)) return false;
  std::string line, cell;
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::stringstream cells(line);
    while (std::getline(cells, cell, ',')) row.push_back(std::strtod(cell.c_str(), nullptr));
    table.rows.push_back(row);
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) {
    std::cerr << "usage: compare_csv A.csv B.csv REL_TOL\n";
    return 2;
  }
  Table a, b;
  if (!read(argv[1], a) || !read(argv[2], b)) {
    std::cerr << "compare_csv: cannot read " << argv[1] << " or " << argv[2] << "\n";
    return 1;
  }
  const double tol = std::strtod(argv[3], nullptr);
  if (a.header != b.header || a.rows.size() != b.rows.size() || a.rows.empty()) {
    std::cerr << "compare_csv: headers or row counts differ (" << a.rows.size() << " vs " << b.rows.size() << " rows)\n"
              << a.header << "\n" << b.header << "\n";
    return 1;
  }
  const std::size_t columns = a.rows[0].size();
  for (std::size_t c = 0; c < columns; ++c) {
    double scale = 0.0;
    for (const auto& row : a.rows) scale = std::max(scale, std::abs(row.at(c)));
    for (std::size_t r = 0; r < a.rows.size(); ++r) {
      if (!(std::abs(a.rows[r].at(c) - b.rows[r].at(c)) <= tol * scale)) {
        std::cerr << "compare_csv: row " << r + 1 << ", column " << c + 1 << ": " << a.rows[r][c] << " vs "
                  << b.rows[r][c] << " (column scale " << scale << ")\n";
        return 1;
      }
    }
  }
  std::cout << "compare_csv: " << a.rows.size() << " rows x " << columns << " columns agree within " << tol
            << " of each column's scale\n";
  return 0;
}
