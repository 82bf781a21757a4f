#pragma once

#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>

#include "ffdkit/cad/cad_model.h"

namespace ffdkit::cad {

/// Limits that keep a hostile CAD file from hanging or exhausting the process.
struct CadReadOptions {
  /// Larger files are refused before they are parsed (bytes; 0 = no limit).
  std::uint64_t maxFileBytes = 512ull << 20;
  /// The transfer of the parsed entities to shapes stops with a CadError after this many
  /// seconds of wall time, and with isolate the reading process after this much CPU time
  /// (0 = no limit).
  double maxSeconds = 120.0;
  /// true: read in a child process (fork), so that a file that makes OpenCASCADE crash or run
  /// away is a CadError, not the end of this process; the parts come back as BRep text.
  bool isolate = true;
  /// With isolate: the child's address-space limit in bytes (0 = none; not applied in
  /// AddressSanitizer builds, whose shadow memory needs more).
  std::uint64_t maxMemoryBytes = 4ull << 30;
};

/// The CAD exchange formats.
enum class CadFormat { Step, Iges };

/// By extension (case-insensitive): .step .stp -> Step, .iges .igs -> Iges, else none.
std::optional<CadFormat> cadFormatOf(const std::filesystem::path& path);

/// Reads a STEP file (AP203, AP214, AP242 geometry): every free shape of the file; an assembly's
/// parts flattened into the model's parts, each placed by the product of its instances' placements
/// and named after its product (or its instance). Lengths in millimetres (OpenCASCADE converts).
/// @throws CadError naming the file and what failed: missing or not a regular file, larger than
///         maxFileBytes, not STEP, a transfer OpenCASCADE throws on or that exceeds maxSeconds,
///         no shape in the file.
CadModel readStep(const std::filesystem::path& path, const CadReadOptions& options = {});
/// The same from a stream; `name` stands for the file in messages.
CadModel readStep(std::istream& in, const std::string& name, const CadReadOptions& options = {});
/// Reads an IGES file (trimmed surfaces, shells and MSBO solids), names from its entity labels.
/// @throws CadError as readStep.
CadModel readIges(const std::filesystem::path& path, const CadReadOptions& options = {});
/// readStep or readIges by extension. @throws CadError on any other extension.
CadModel readCad(const std::filesystem::path& path, const CadReadOptions& options = {});

/// Writes the model as STEP AP214 (one product per part, named), into a temporary file beside
/// `path` renamed onto it when complete (a failure leaves `path` as it was).
/// @throws CadError naming the file when OpenCASCADE cannot transfer or write it.
void writeStep(const CadModel& model, const std::filesystem::path& path);
/// Writes the model as IGES 5.3 in BRep mode (solids as MSBO entities), atomically as writeStep.
void writeIges(const CadModel& model, const std::filesystem::path& path);
/// writeStep or writeIges by extension. @throws CadError on any other extension.
void writeCad(const CadModel& model, const std::filesystem::path& path);

}  // namespace ffdkit::cad
