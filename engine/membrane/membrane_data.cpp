#include "engine/membrane/membrane_data.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <istream>
#include <ostream>
#include <sstream>

#include "engine/core/error.h"
#include "engine/core/file_input.h"
#include "engine/core/parse.h"

namespace cablelab {
namespace {

constexpr std::array<const char*, 4> kColumns = {"x", "y", "fy", "angle_deg"};

std::string trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return {};
  const auto last = s.find_last_not_of(" \t\r\n");
  return s.substr(first, last - first + 1);
}

std::vector<std::string> splitCommas(const std::string& line) {
  std::vector<std::string> fields;
  std::string field;
  std::istringstream in(line);
  while (std::getline(in, field, ',')) fields.push_back(trim(field));
  if (!line.empty() && line.back() == ',') fields.emplace_back();  // getline drops a last empty
  return fields;
}

std::string rowField(int row, const std::string& column) {
  return "row " + std::to_string(row) + (column.empty() ? "" : ", " + column);
}

double parseField(const std::string& text, int row, const std::string& column,
                  const std::string& source) {
  const auto value = parseFiniteNumber(text);
  if (!value)
    throw InputError(source, rowField(row, column), "must be a finite number" + gotValue(text));
  return *value;
}

}  // namespace

void validateMembraneGeometry(const MembraneGeometry& g, const std::string& source,
                              const std::string& field) {
  const std::string got = " (got " + formatNumber(g.a.x()) + "," + formatNumber(g.a.y()) + "," +
                          formatNumber(g.b.x()) + "," + formatNumber(g.b.y()) + ")";
  if (!isFinite(g.a) || !isFinite(g.b))
    throw InputError(source, field, "coordinates must be finite" + got);
  const double span = (g.b - g.a).norm();
  const double scale = std::max({1.0, g.a.norm(), g.b.norm()});
  if (span <= 1e-12 * scale)
    throw InputError(source, field, "pulleys A and B coincide: the band has no direction" + got);
}

void validateMembranePoint(const MembraneGeometry& g, const Vec2& p, int row,
                           const std::string& source) {
  if (!isFinite(p))
    throw InputError(
        source, rowField(row, "x"),
        "must be finite (got [" + formatNumber(p.x()) + ", " + formatNumber(p.y()) + "])");
  const double span = (g.b - g.a).norm();
  // A point on a pulley has no unit vector u_i; one between them has u1 + u2 = 0.
  const std::string got = " (got [" + formatNumber(p.x()) + ", " + formatNumber(p.y()) + "])";
  for (const auto& [pulley, name] : {std::pair{g.a, "A"}, std::pair{g.b, "B"}})
    if ((p - pulley).norm() <= 1e-12 * span)
      throw InputError(source, rowField(row, "x"),
                       std::string("point coincides with pulley ") + name + got);
  if (membraneDirectionSum(g, p).norm() < kMembraneOnLineTolerance)
    throw InputError(source, rowField(row, "y"),
                     "point lies on the band between the pulleys: force direction undefined" + got);
}

std::vector<MembraneSample> parseMembraneCsv(std::istream& in, const MembraneGeometry& g,
                                             const std::string& source) {
  validateMembraneGeometry(g, source);  // callers usually checked it already, naming their flag
  std::string line;
  std::vector<std::string> header;
  while (header.empty() && std::getline(in, line)) {
    if (line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);  // UTF-8 byte-order mark
    if (!trim(line).empty()) header = splitCommas(line);
  }
  if (header.empty())
    throw InputError(source, "header", "file is empty (expected x,y,fy,angle_deg)" + gotValue(""));

  std::array<int, 4> index{};
  for (size_t c = 0; c < kColumns.size(); ++c) {
    index[c] = -1;
    for (size_t h = 0; h < header.size(); ++h) {
      if (header[h] != kColumns[c]) continue;
      if (index[c] >= 0)
        throw InputError(
            source, "header",
            std::string("column \"") + kColumns[c] + "\" appears twice" + gotValue(line));
      index[c] = static_cast<int>(h);
    }
    if (index[c] < 0)
      throw InputError(source, "header",
                       std::string("missing column \"") + kColumns[c] +
                           "\" (expected x,y,fy,angle_deg)" + gotValue(line));
  }

  std::vector<MembraneSample> rows;
  int row = 0;
  while (std::getline(in, line)) {
    if (trim(line).empty()) continue;
    ++row;
    const auto fields = splitCommas(line);
    if (fields.size() != header.size())
      throw InputError(source, rowField(row, ""),
                       "expected " + std::to_string(header.size()) + " fields" +
                           gotValue(static_cast<double>(fields.size())));
    std::array<double, 4> v{};
    for (size_t c = 0; c < kColumns.size(); ++c)
      v[c] = parseField(fields[index[c]], row, kColumns[c], source);
    MembraneSample sample{Vec2(v[0], v[1]), v[2], v[3]};
    validateMembranePoint(g, sample.p, row, source);
    rows.push_back(sample);
  }
  if (static_cast<int>(rows.size()) < kMinMembraneRows)
    throw InputError(source, "rows",
                     "need at least " + std::to_string(kMinMembraneRows) +
                         " measurements to fit k and preload (got " + std::to_string(rows.size()) +
                         ")");
  return rows;
}

std::vector<MembraneSample> loadMembraneCsv(const std::string& path, const MembraneGeometry& g) {
  std::istringstream in(readInputFile(path));
  return parseMembraneCsv(in, g, path);
}

void writeMembraneCsv(std::ostream& out, const std::vector<MembraneSample>& rows) {
  out << "x,y,fy,angle_deg\n";
  char buffer[128];
  for (const auto& s : rows) {
    std::snprintf(buffer, sizeof buffer, "%.17g,%.17g,%.17g,%.17g\n", s.p.x(), s.p.y(), s.fy,
                  s.angleDeg);
    out << buffer;
  }
}

}  // namespace cablelab
