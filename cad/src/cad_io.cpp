// STEP and IGES through OpenCASCADE's XDE readers and writers (names and assemblies kept).
#include "ffdkit/cad/cad_io.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <fstream>
#include <system_error>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <sstream>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <BRepTools.hxx>
#include <BRep_Builder.hxx>

#include <IFSelect_ReturnStatus.hxx>
#include <IGESCAFControl_Reader.hxx>
#include <IGESCAFControl_Writer.hxx>
#include <IGESControl_Controller.hxx>
#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_PrinterOStream.hxx>
#include <Message_ProgressIndicator.hxx>
#include <STEPCAFControl_Reader.hxx>
#include <STEPCAFControl_Writer.hxx>
#include <STEPControl_Controller.hxx>
#include <STEPControl_Reader.hxx>
#include <TCollection_AsciiString.hxx>
#include <TCollection_ExtendedString.hxx>
#include <TDF_Label.hxx>
#include <TDF_LabelSequence.hxx>
#include <TDataStd_Name.hxx>
#include <TDocStd_Document.hxx>
#include <TopLoc_Location.hxx>
#include <XCAFApp_Application.hxx>
#include <XCAFDoc_DocumentTool.hxx>
#include <XCAFDoc_ShapeTool.hxx>

#include "cad_model_data.h"

// AddressSanitizer reserves terabytes of shadow address space: no address-space limit under it.
#if defined(__SANITIZE_ADDRESS__)
#define FFDKIT_CAD_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define FFDKIT_CAD_ASAN 1
#endif
#endif
#ifndef FFDKIT_CAD_ASAN
#define FFDKIT_CAD_ASAN 0
#endif

namespace ffdkit::cad {

namespace {

namespace fs = std::filesystem;

/// OpenCASCADE prints its readers' and writers' traces on stdout by default: the CLI's output is
/// ours, so its printers go (once per process).
void silenceOcct() {
  static const bool done = [] {
    Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_PrinterOStream));
    return true;
  }();
  (void)done;
}

/// Asks OpenCASCADE's transfer to stop once `seconds` of wall time have passed (0: never).
class DeadlineProgress : public Message_ProgressIndicator {
 public:
  explicit DeadlineProgress(double seconds) : seconds_(seconds), start_(std::chrono::steady_clock::now()) {}
  Standard_Boolean UserBreak() override { return expired(); }
  void Show(const Message_ProgressScope&, const Standard_Boolean) override {}
  bool expired() const {
    return seconds_ > 0.0 && std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count() > seconds_;
  }

 private:
  double seconds_;
  std::chrono::steady_clock::time_point start_;
};

/// A fresh XDE document, closed when it goes.
class XdeDocument {
 public:
  XdeDocument() {
    app_ = XCAFApp_Application::GetApplication();
    app_->NewDocument("MDTV-XCAF", doc_);
  }
  ~XdeDocument() {
    try {
      if (!doc_.IsNull() && app_->CanClose(doc_) == CDM_CCS_OK) app_->Close(doc_);
    } catch (const Standard_Failure&) {
    }
  }
  XdeDocument(const XdeDocument&) = delete;
  XdeDocument& operator=(const XdeDocument&) = delete;
  Handle(TDocStd_Document)& doc() { return doc_; }
  Handle(XCAFDoc_ShapeTool) shapes() const { return XCAFDoc_DocumentTool::ShapeTool(doc_->Main()); }

 private:
  Handle(XCAFApp_Application) app_;
  Handle(TDocStd_Document) doc_;
};

std::string labelName(const TDF_Label& label) {
  Handle(TDataStd_Name) name;
  if (!label.FindAttribute(TDataStd_Name::GetID(), name)) return {};
  return TCollection_AsciiString(name->Get()).ToCString();
}

/// Appends the simple shapes under `label` (an assembly's components recursively) as parts placed
/// by the product of the placements on the way.
void collectParts(const Handle(XCAFDoc_ShapeTool)& tool, const TDF_Label& label, const TopLoc_Location& placement,
                  const std::string& instanceName, int depth, const std::string& file, std::vector<CadPartData>& parts) {
  if (depth > 64) throw CadError(file + ": assembly nesting deeper than 64 levels (a loop of instances?)");
  TDF_Label referred = label;
  if (tool->IsReference(label)) tool->GetReferredShape(label, referred);
  std::string name = labelName(referred);
  if (name.empty()) name = instanceName;
  if (tool->IsAssembly(referred)) {
    TDF_LabelSequence components;
    tool->GetComponents(referred, components);
    for (Standard_Integer i = 1; i <= components.Length(); ++i) {
      const TDF_Label& component = components.Value(i);
      collectParts(tool, component, placement * tool->GetLocation(component), labelName(component), depth + 1, file,
                   parts);
    }
    return;
  }
  const TopoDS_Shape shape = tool->GetShape(referred);
  if (!shape.IsNull()) parts.push_back({name, shape.Moved(placement)});
}

CadModel modelFromDocument(XdeDocument& document, const std::string& file) {
  const Handle(XCAFDoc_ShapeTool) tool = document.shapes();
  TDF_LabelSequence free;
  tool->GetFreeShapes(free);
  CadModel model;
  for (Standard_Integer i = 1; i <= free.Length(); ++i)
    collectParts(tool, free.Value(i), TopLoc_Location(), "", 0, file, model.data().parts);
  if (model.data().parts.empty()) throw CadError(file + ": the file holds no shape");
  int unnamed = 0;
  for (auto& part : model.data().parts)
    if (part.name.empty()) part.name = "part-" + std::to_string(++unnamed);
  return model;
}

void checkFile(const fs::path& path, const CadReadOptions& options) {
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  if (error || !fs::exists(status)) throw CadError(path.string() + ": no such file");
  if (!fs::is_regular_file(status)) throw CadError(path.string() + ": not a regular file");
  const std::uintmax_t size = fs::file_size(path, error);
  if (error) throw CadError(path.string() + ": cannot read its size (" + error.message() + ")");
  if (options.maxFileBytes > 0 && size > options.maxFileBytes)
    throw CadError(path.string() + ": " + std::to_string(size) + " bytes is more than the limit of " +
                   std::to_string(options.maxFileBytes) + " (CadReadOptions::maxFileBytes)");
  std::ifstream probe(path, std::ios::binary);
  if (!probe) throw CadError(path.string() + ": cannot open the file for reading");
}

/// Transfers what `reader` parsed into a document, under the time limit.
template <class Reader>
CadModel transfer(Reader& reader, const std::string& file, const char* format, const CadReadOptions& options) {
  XdeDocument document;
  Handle(DeadlineProgress) progress = new DeadlineProgress(options.maxSeconds);
  const bool done = guardOcct(file + ": transferring the entities to shapes",
                              [&] { return static_cast<bool>(reader.Transfer(document.doc(), progress->Start())); });
  if (progress->expired())
    throw CadError(file + ": the transfer took more than " + std::to_string(options.maxSeconds) +
                   " s (CadReadOptions::maxSeconds)");
  if (!done) throw CadError(file + ": OpenCASCADE could not transfer the file's " + format + " entities to shapes");
  return guardOcct(file + ": collecting the parts", [&] { return modelFromDocument(document, file); });
}

std::string statusText(IFSelect_ReturnStatus status) {
  switch (status) {
    case IFSelect_RetVoid: return "nothing to read";
    case IFSelect_RetError: return "a syntax error";
    case IFSelect_RetFail: return "a failure to read";
    case IFSelect_RetStop: return "the reader stopped";
    default: return "status " + std::to_string(static_cast<int>(status));
  }
}

std::string lowerExtension(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

/// Writes through `write(temporaryPath)` and renames the result onto `path`.
template <class Write>
void writeAtomically(const fs::path& path, Write&& write) {
  const fs::path target = path.has_parent_path() ? path : fs::path(".") / path;
  const fs::path temporary =
      target.parent_path() / ("." + target.filename().string() + ".tmp-" + std::to_string(::getpid()));
  try {
    write(temporary);
    std::error_code error;
    fs::rename(temporary, target, error);
    if (error) throw CadError(path.string() + ": cannot move the written file into place (" + error.message() + ")");
  } catch (...) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw;
  }
}

/// A document holding each part as a named free shape.
void fillDocument(XdeDocument& document, const CadModel& model) {
  const Handle(XCAFDoc_ShapeTool) tool = document.shapes();
  for (const auto& part : model.data().parts) {
    const TDF_Label label = tool->AddShape(part.shape, false);
    const TCollection_ExtendedString name(part.name.c_str(), true);
    TDataStd_Name::Set(label, name);
    TDF_Label referred;
    if (tool->GetReferredShape(label, referred)) TDataStd_Name::Set(referred, name);
  }
}

}  // namespace

std::optional<CadFormat> cadFormatOf(const fs::path& path) {
  const std::string ext = lowerExtension(path);
  if (ext == ".step" || ext == ".stp") return CadFormat::Step;
  if (ext == ".iges" || ext == ".igs") return CadFormat::Iges;
  return std::nullopt;
}

namespace {

CadModel readStepHere(const fs::path& path, const CadReadOptions& options) {
  silenceOcct();
  const std::string file = path.string();
  STEPCAFControl_Reader reader;
  reader.SetNameMode(true);
  const IFSelect_ReturnStatus status =
      guardOcct(file + ": reading STEP", [&] { return reader.ReadFile(file.c_str()); });
  if (status != IFSelect_RetDone) throw CadError(file + ": not a readable STEP file (" + statusText(status) + ")");
  return transfer(reader, file, "STEP", options);
}

CadModel readStepHere(std::istream& in, const std::string& name, const CadReadOptions& options) {
  silenceOcct();
  STEPCAFControl_Reader reader;
  reader.SetNameMode(true);
  const IFSelect_ReturnStatus status =
      guardOcct(name + ": reading STEP", [&] { return reader.ChangeReader().ReadStream(name.c_str(), in); });
  if (status != IFSelect_RetDone) throw CadError(name + ": not a readable STEP file (" + statusText(status) + ")");
  return transfer(reader, name, "STEP", options);
}

CadModel readIgesHere(const fs::path& path, const CadReadOptions& options) {
  silenceOcct();
  const std::string file = path.string();
  IGESCAFControl_Reader reader;
  reader.SetNameMode(true);
  const IFSelect_ReturnStatus status =
      guardOcct(file + ": reading IGES", [&] { return reader.ReadFile(file.c_str()); });
  if (status != IFSelect_RetDone) throw CadError(file + ": not a readable IGES file (" + statusText(status) + ")");
  return transfer(reader, file, "IGES", options);
}

/// The parts as text: a header, then per part its name and its shape in BRep text form.
void writeParts(const CadModel& model, std::ostream& out) {
  out << "ffdkit-cad-parts 1\n" << model.data().parts.size() << "\n";
  for (const auto& part : model.data().parts) {
    std::ostringstream brep;
    BRepTools::Write(part.shape, brep);
    const std::string text = brep.str();
    out << part.name.size() << "\n" << part.name << "\n" << text.size() << "\n" << text;
  }
}

CadModel readParts(std::istream& in, const std::string& file) {
  std::string magic;
  std::size_t count = 0;
  if (!(in >> magic >> magic) || !(in >> count) || count > 1000000) throw CadError(file + ": the reading process returned no parts");
  CadModel model;
  for (std::size_t i = 0; i < count; ++i) {
    std::size_t nameSize = 0, brepSize = 0;
    in >> nameSize;
    in.get();
    std::string name(nameSize, '\0');
    in.read(name.data(), static_cast<std::streamsize>(nameSize));
    in >> brepSize;
    in.get();
    std::string brep(brepSize, '\0');
    in.read(brep.data(), static_cast<std::streamsize>(brepSize));
    if (!in) throw CadError(file + ": the reading process returned a truncated part list");
    std::istringstream shapeText(brep);
    TopoDS_Shape shape;
    BRep_Builder builder;
    guardOcct(file + ": reading back a part", [&] { BRepTools::Read(shape, shapeText, builder); });
    model.data().parts.push_back({name, shape});
  }
  return model;
}

/// Runs `read` in a child process, so that a file that makes OpenCASCADE crash (it dereferences
/// null entities of some malformed files) or run away is a CadError here: the child has
/// maxSeconds of CPU time (SIGXCPU) and, outside sanitizer builds, maxMemoryBytes of address space;
/// it hands the parts back as BRep text through a temporary file.
CadModel readIsolated(const std::string& file, const CadReadOptions& options, const std::function<CadModel()>& read) {
  if (!options.isolate) return read();
  char pattern[] = "/tmp/ffdkit-cad-read-XXXXXX";
  const int fd = ::mkstemp(pattern);
  if (fd < 0) throw CadError(file + ": cannot create a temporary file for the reading process");
  ::close(fd);
  const std::string transferFile = pattern;
  std::fflush(nullptr);
  const pid_t child = ::fork();
  if (child < 0) {
    ::unlink(transferFile.c_str());
    throw CadError(file + ": cannot start the reading process");
  }
  if (child == 0) {
#if !FFDKIT_CAD_ASAN
    if (options.maxMemoryBytes > 0) {
      const rlimit memory{options.maxMemoryBytes, options.maxMemoryBytes};
      ::setrlimit(RLIMIT_AS, &memory);
    }
#endif
    if (options.maxSeconds > 0) {
      const rlim_t seconds = static_cast<rlim_t>(std::ceil(options.maxSeconds));
      const rlimit cpu{seconds, seconds + 1};
      ::setrlimit(RLIMIT_CPU, &cpu);
    }
    int code = 0;
    std::ofstream out(transferFile, std::ios::binary | std::ios::trunc);
    try {
      writeParts(read(), out);
    } catch (const CadError& error) {
      out << "error\n" << error.what();
      code = 3;
    } catch (const std::bad_alloc&) {
      code = 4;
    } catch (...) {
      code = 5;
    }
    out.close();
    std::_Exit(code);
  }
  int status = 0;
  while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {
  }
  std::ifstream in(transferFile, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ::unlink(transferFile.c_str());
  if (WIFSIGNALED(status)) {
    const int signal = WTERMSIG(status);
    if (signal == SIGXCPU || signal == SIGKILL)
      throw CadError(file + ": reading took more than " + std::to_string(options.maxSeconds) +
                     " s of CPU time (CadReadOptions::maxSeconds)");
    throw CadError(file + ": OpenCASCADE crashed reading the file (signal " + std::to_string(signal) + ")");
  }
  const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  if (code == 3) throw CadError(text.substr(text.find('\n') + 1));
  if (code == 4)
    throw CadError(file + ": reading needs more than " + std::to_string(options.maxMemoryBytes) +
                   " bytes of memory (CadReadOptions::maxMemoryBytes)");
  if (code == 5) throw CadError(file + ": the reading process failed (exit status 5: an unexpected exception)");
  // Any other status is not one the child chose: the process ended abnormally (under ASan a
  // crash is reported and ends the process with ASan's exit code instead of the signal).
  if (code != 0)
    throw CadError(file + ": OpenCASCADE crashed reading the file (the reading process ended with exit status " +
                   std::to_string(code) + ")");
  std::istringstream parts(text);
  return readParts(parts, file);
}

}  // namespace

CadModel readStep(const fs::path& path, const CadReadOptions& options) {
  checkFile(path, options);
  return readIsolated(path.string(), options, [&] { return readStepHere(path, options); });
}

CadModel readStep(std::istream& in, const std::string& name, const CadReadOptions& options) {
  return readIsolated(name, options, [&] { return readStepHere(in, name, options); });
}

CadModel readIges(const fs::path& path, const CadReadOptions& options) {
  checkFile(path, options);
  return readIsolated(path.string(), options, [&] { return readIgesHere(path, options); });
}

CadModel readCad(const fs::path& path, const CadReadOptions& options) {
  const auto format = cadFormatOf(path);
  if (!format) throw CadError(path.string() + ": not a CAD file name (expected .step, .stp, .iges or .igs)");
  return *format == CadFormat::Step ? readStep(path, options) : readIges(path, options);
}

void writeStep(const CadModel& model, const fs::path& path) {
  silenceOcct();
  const std::string file = path.string();
  writeAtomically(path, [&](const fs::path& temporary) {
    guardOcct(file + ": writing STEP", [&] {
      STEPControl_Controller::Init();
      Interface_Static::SetCVal("write.step.schema", "AP214IS");
      XdeDocument document;
      fillDocument(document, model);
      STEPCAFControl_Writer writer;
      writer.SetNameMode(true);
      if (!writer.Transfer(document.doc(), STEPControl_AsIs))
        throw CadError(file + ": OpenCASCADE could not transfer the shapes to STEP entities");
      const IFSelect_ReturnStatus status = writer.Write(temporary.string().c_str());
      if (status != IFSelect_RetDone) throw CadError(file + ": writing the STEP file failed (" + statusText(status) + ")");
    });
  });
}

void writeIges(const CadModel& model, const fs::path& path) {
  silenceOcct();
  const std::string file = path.string();
  writeAtomically(path, [&](const fs::path& temporary) {
    guardOcct(file + ": writing IGES", [&] {
      IGESControl_Controller::Init();
      Interface_Static::SetIVal("write.iges.brep.mode", 1);
      XdeDocument document;
      fillDocument(document, model);
      IGESCAFControl_Writer writer;
      writer.SetNameMode(true);
      if (!writer.Transfer(document.doc()))
        throw CadError(file + ": OpenCASCADE could not transfer the shapes to IGES entities");
      if (!writer.Write(temporary.string().c_str())) throw CadError(file + ": writing the IGES file failed");
    });
  });
}

void writeCad(const CadModel& model, const fs::path& path) {
  const auto format = cadFormatOf(path);
  if (!format) throw CadError(path.string() + ": not a CAD file name (expected .step, .stp, .iges or .igs)");
  if (*format == CadFormat::Step)
    writeStep(model, path);
  else
    writeIges(model, path);
}

}  // namespace ffdkit::cad
