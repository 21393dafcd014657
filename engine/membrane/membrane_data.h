// Membrane force measurements (thesis chapter 3): loading, validating and writing the CSV.
//
// File format: a header line naming the columns, then one measurement per line:
//
//   x,y,fy,angle_deg
//   0.05,-0.08,6.93,81.2
//
//   x, y       contact point in the world frame (m)
//   fy         measured vertical (world y) component of the band's force on the point (N)
//   angle_deg  measured direction of that force, atan2(F_y, F_x) in degrees, counter-clockwise
//              from +x; any finite value (it is compared modulo 360)
//
// Columns may come in any order; extra columns are ignored; blank lines are skipped.
// "row N" in errors is the N-th measurement line (row 1 is the first line after the header).
// Every problem throws cablelab::InputError(file, "row N: column", what).
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "engine/membrane/membrane_model.h"

namespace cablelab {

/// One measurement.
struct MembraneSample {
  Vec2 p = Vec2::Zero();  ///< contact point, world (m)
  double fy = 0.0;        ///< measured vertical force component (N)
  double angleDeg = 0.0;  ///< measured force direction, atan2(F_y, F_x) (degrees)
};

/// Fewer rows than this cannot tell k and preload apart from noise.
inline constexpr int kMinMembraneRows = 3;

/// Below this |u1 + u2| (dimensionless) a point counts as lying on the segment between the
/// pulleys, where the band's force is zero and its direction undefined.
inline constexpr double kMembraneOnLineTolerance = 1e-9;

/// Throws InputError(source, "pulleys", ...) if A or B is not finite or they coincide.
void validateMembraneGeometry(const MembraneGeometry& g, const std::string& source,
                              const std::string& field = "pulleys");

/// Throws InputError(source, "row N: x", ...) if the point is not finite, sits on a pulley or
/// on the segment between them; `row` is 1-based.
void validateMembranePoint(const MembraneGeometry& g, const Vec2& p, int row,
                           const std::string& source);

/// Parses and validates CSV text. `source` names the file in error messages.
/// @return the rows in file order (at least kMinMembraneRows)
std::vector<MembraneSample> parseMembraneCsv(std::istream& in, const MembraneGeometry& g,
                                             const std::string& source);

/// Opens `path` and parses it (see parseMembraneCsv); a missing file is an InputError too.
std::vector<MembraneSample> loadMembraneCsv(const std::string& path, const MembraneGeometry& g);

/// Writes the header and rows with full double precision (17 significant digits).
void writeMembraneCsv(std::ostream& out, const std::vector<MembraneSample>& rows);

}  // namespace cablelab
