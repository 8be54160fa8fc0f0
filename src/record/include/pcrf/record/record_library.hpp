/// \file record_library.hpp
/// \brief The response spectra of a library of records, computed once and kept as a table
/// that record selection reads (`pcrf record spectra`, `pcrf record select`).
///
/// A library is every PEER `.AT2` file of a folder (and its subfolders), or a list of files.
/// Vertical channels (is_vertical_component) are left out. Files whose names differ only in the
/// component after the last '_' ("RSN1063_NORTHR_RRS228", "…_RRS318") in one folder are a
/// station; a station with exactly two horizontals whose azimuths the names state is a pair.
/// Each horizontal is an entry of kind "component"; each pair also gives an entry of kind
/// "rotd50", the median over azimuths of the pair's Sa (rotd.hpp, Boore 2010). The Sa are
/// those of spectral_acceleration_g and rotd(): the exact piecewise-linear response.
///
/// The table (CSV, '#' comment lines first) has one row per entry:
///     name,kind,file,file_h2,dt_s,samples,damping,pga_g,sa_g_<T>s,…
/// with one Sa column per period of the grid, in increasing order.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <istream>
#include <ostream>
#include <string>
#include <vector>

namespace pcrf {

struct LibraryEntry {
  std::string name;          ///< the file stem, or for a pair's RotD50 the station's ("RSN1063_NORTHR")
  std::string kind;          ///< "component" or "rotd50"
  std::string file;          ///< the (first) component's file, as found
  std::string file_h2;       ///< the pair's second horizontal ("" for a component)
  double dt_s = 0.0;
  std::size_t samples = 0;
  double damping = 0.05;
  double pga_g = 0.0;        ///< the component's PGA, or the pair's PGA RotD50 [g]
  std::vector<double> sa_g;  ///< at the table's periods [g]
};

struct SpectraTable {
  std::vector<double> periods_s;  ///< increasing
  std::vector<LibraryEntry> entries;
};

/// The default grid: 30 periods from 0.05 s to 10 s, evenly spaced in ln T (4 significant digits).
std::vector<double> default_spectra_periods_s();

/// The `.AT2` files under each of `paths` (a folder, searched recursively, or a file), sorted,
/// each file name once (a name found again in another folder is left out: `skipped` says so).
std::vector<std::filesystem::path> library_files(const std::vector<std::filesystem::path>& paths,
                                                 std::vector<std::string>& skipped);

/// Why a grid cannot be used ("" when it can): empty, not increasing, or a period that is not
/// positive and finite or above kMaxSaPeriod_s.
std::string periods_problem(const std::vector<double>& periods_s);

/// The spectra of every entry of `files`. `progress(done, total, file)` is called before each
/// file. A file that cannot be read, or whose dt cannot resolve the shortest period, is left
/// out with a line in `skipped`.
/// \throws UserError for a bad grid or damping.
SpectraTable compute_spectra(const std::vector<std::filesystem::path>& files, const std::vector<double>& periods_s,
                             double damping, std::vector<std::string>& skipped,
                             const std::function<void(std::size_t, std::size_t, const std::string&)>& progress = {});

/// Writes the table as CSV.
void write_spectra_csv(std::ostream& out, const SpectraTable& table);
/// Reads a table written by write_spectra_csv. `file` names it in messages.
/// \throws UserError naming the file, the line and the column for anything malformed: a header
/// without the fixed columns or with periods that are not increasing, a row with the wrong
/// number of fields, a value that is not a finite number (Sa ≤ 0 included), an unknown kind.
SpectraTable read_spectra_csv(std::istream& in, const std::string& file);

}  // namespace pcrf
