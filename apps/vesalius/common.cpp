#include "common.h"

#include "vesalius/core/error.h"
#include "vesalius/io/motion_io.h"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace vesalius::cli {

namespace {

namespace fs = std::filesystem;

// The current command's input files, for messages from library code that knows no file name.
std::vector<std::string>& commandInputs() {
  static std::vector<std::string> inputs;
  return inputs;
}

// Output options are named so: --out, --out-*, --*-out, --png, --png-*, --*-png and --report. Every other
// option or argument whose value names an existing file or folder is an input.
bool isOutputOption(const std::string& name) {
  const auto endsWith = [&](const std::string& tail) {
    return name.size() >= tail.size() && name.compare(name.size() - tail.size(), tail.size(), tail) == 0;
  };
  return name == "--out" || name.rfind("--out-", 0) == 0 || endsWith("-out") || name == "--png" ||
         name.rfind("--png-", 0) == 0 || endsWith("-png") || name == "--report";
}

// The same file or folder: by device and inode when both exist, else by their normalised absolute paths.
bool samePath(const std::string& a, const std::string& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec);
  return fs::weakly_canonical(a, ec) == fs::weakly_canonical(b, ec);
}

// Before any work: no output is an input (also through a symlink or a hard link), and no two outputs are
// one file. Inputs are also protected for the rest of the run (core/atomic_file.h), so that an output
// derived from another (a label table beside a label map, a mesh named after a label) cannot replace one.
void checkInputsAndOutputs(const CLI::App& command) {
  struct Named {
    std::string option, path;
  };
  std::vector<Named> inputs, outputs;
  for (const CLI::Option* option : command.get_options()) {
    if (option->count() == 0 || option->get_expected_max() == 0) continue;  // unset, or a flag
    const std::string name = option->get_name();
    for (const std::string& value : option->results()) {
      if (value.empty()) continue;
      std::error_code ec;
      if (isOutputOption(name))
        outputs.push_back({name, value});
      else if (fs::exists(value, ec))
        inputs.push_back({name, value});
    }
  }
  // Whether `folder` is on the path of another output: that output (a folder the command makes, e.g. --out),
  // inside it, or a folder that holds it (made with it). A report written into --out, or beside a folder
  // --out names, is checked with that output's own folder.
  // Absolute and normal, without the empty last element that "x/y/.." normalises to ("x/").
  const auto normal = [](const fs::path& p) {
    std::error_code ec;
    const fs::path n = fs::weakly_canonical(p, ec);
    return n.has_filename() ? n : n.parent_path();
  };
  const auto onAnotherOutput = [&](const fs::path& folder, const Named& self) {
    const fs::path a = normal(folder);
    for (const Named& other : outputs) {
      if (&other == &self) continue;
      const fs::path b = normal(other.path);
      if (std::mismatch(a.begin(), a.end(), b.begin(), b.end()).first == a.end() ||
          std::mismatch(b.begin(), b.end(), a.begin(), a.end()).first == b.end())
        return true;
    }
    return false;
  };
  for (const Named& output : outputs) {
    // Said now, not when the first file is written after the work.
    struct stat info {};
    if (::stat(output.path.c_str(), &info) != 0 && errno == ENAMETOOLONG)
      throw UsageError(output.path + ": " + output.option + " names a path too long for the file system");
    std::error_code ec;
    const fs::path folder = fs::path(output.path).has_parent_path() ? fs::path(output.path).parent_path() : fs::path(".");
    if (onAnotherOutput(folder, output)) continue;
    if (!fs::is_directory(folder, ec))
      throw UsageError(output.path + ": " + output.option + " is in the folder " + folder.string() +
                       ", which does not exist");
    if (::access(folder.c_str(), W_OK) != 0)
      throw UsageError(output.path + ": " + output.option + " is in the folder " + folder.string() +
                       ", which is not writable");
  }
  for (const Named& input : inputs) {
    protectInput(input.path);
    commandInputs().push_back(input.path);
  }
  for (std::size_t o = 0; o < outputs.size(); ++o) {
    for (const Named& input : inputs)
      if (samePath(outputs[o].path, input.path))
        throw UsageError(outputs[o].path + ": " + outputs[o].option + " names the input " + input.option + " " +
                         input.path + "; an output never replaces an input, --force or not");
    for (std::size_t other = 0; other < o; ++other)
      if (samePath(outputs[o].path, outputs[other].path))
        throw UsageError(outputs[o].path + ": given to both " + outputs[other].option + " and " + outputs[o].option);
  }
}

}  // namespace

namespace {

struct SlicerAnnotation {
  SlicerKind kind;
  bool output;
  std::string fileExtensions;
};

// Filled while the commands are set up, read by slicerXml; the options live as long as the app.
std::map<const CLI::Option*, SlicerAnnotation>& slicerAnnotations() {
  static std::map<const CLI::Option*, SlicerAnnotation> annotations;
  return annotations;
}

std::string xmlEscaped(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '&') out += "&amp;";
    else if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '"') out += "&quot;";
    else out += c;
  }
  return out;
}

// "skin-thickness" -> "skin_thickness": Slicer's <name> and <longflag> take letters, digits and '_' only.
std::string slicerName(std::string name) {
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  if (name.empty() || std::isdigit(static_cast<unsigned char>(name[0]))) name = "_" + name;
  return name;
}

// "skin-thickness" -> "Skin thickness".
std::string slicerLabel(const std::string& name) {
  std::string label = name;
  for (char& c : label)
    if (c == '-' || c == '_') c = ' ';
  if (!label.empty()) label[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(label[0])));
  return label;
}

// The members of an IsMember check, from CLI11's type name "TEXT:{ct,mri}"; empty without one.
std::vector<std::string> enumerationElements(const CLI::Option& option) {
  const std::string type = option.get_type_name();
  const std::size_t open = type.find(":{");
  const std::size_t close = type.find('}', open);
  std::vector<std::string> elements;
  if (open == std::string::npos || close == std::string::npos) return elements;
  std::stringstream list(type.substr(open + 2, close - open - 2));
  for (std::string element; std::getline(list, element, ',');) elements.push_back(element);
  return elements;
}

bool mentionsFolder(const std::string& description) {
  return description.find("folder") != std::string::npos || description.find("directory") != std::string::npos ||
         description.find("Folder") != std::string::npos || description.find("Directory") != std::string::npos;
}

struct SlicerParameterXml {
  std::string tag, attributes;
  bool channel = false, output = false;
  std::vector<std::string> elements;
  std::string defaultValue;
};

SlicerParameterXml slicerParameterXml(const CLI::Option& option, const std::string& longName) {
  SlicerParameterXml p;
  const std::string flag = "--" + longName;
  const auto annotated = slicerAnnotations().find(&option);
  if (annotated != slicerAnnotations().end()) {
    const SlicerAnnotation& a = annotated->second;
    static const char* const kTags[] = {"image", "image", "geometry", "file", "directory"};
    p.tag = kTags[static_cast<int>(a.kind)];
    if (a.kind == SlicerKind::LabelImage) p.attributes += " type=\"label\"";
    if (!a.fileExtensions.empty()) p.attributes += " fileExtensions=\"" + xmlEscaped(a.fileExtensions) + "\"";
    p.channel = a.kind != SlicerKind::Directory;  // <directory> has no channel in the schema
    p.output = a.output;
    return p;
  }
  if (option.get_expected_max() == 0) {
    p.tag = "boolean";
    p.defaultValue = "false";
    return p;
  }
  p.elements = enumerationElements(option);
  if (!p.elements.empty()) {
    p.tag = "string-enumeration";
    p.defaultValue = flag == "--progress" ? "slicer" : option.get_default_str();
    if (std::find(p.elements.begin(), p.elements.end(), p.defaultValue) == p.elements.end())
      p.defaultValue = p.elements.front();
    return p;
  }
  const std::string type = option.get_type_name().substr(0, option.get_type_name().find(':'));
  if (type == "INT" || type == "UINT") {
    p.tag = "integer";
  } else if (type == "FLOAT") {
    p.tag = "double";
  } else if (flag == "--scan") {
    p.tag = "image";
    p.channel = true;
  } else if (flag == "--labels" || flag == "--organs") {
    p.tag = "image";
    p.attributes = " type=\"label\"";
    p.channel = true;
  } else if (!longName.empty() && isOutputOption(flag)) {
    p.tag = mentionsFolder(option.get_description()) ? "directory" : "file";
    p.channel = p.tag == "file";
    p.output = true;
  } else {
    p.tag = "string";
  }
  if (option.get_expected_max() > 1) p.attributes += " multiple=\"true\"";
  if (p.tag != "image") p.defaultValue = option.get_default_str();
  return p;
}

// The long name Slicer passes: a flag's negated name when it has one besides its own ("--cor-centres,
// !--no-cor-centres": Slicer's check box, unchecked by default, can only add a flag, and the flag's default
// is on); else the first.
std::string slicerLongName(const CLI::Option& option) {
  const std::vector<std::string>& longNames = option.get_lnames();
  if (longNames.empty()) return {};
  if (option.get_expected_max() == 0)
    for (const std::string& name : longNames)
      for (const std::string& withValue : option.get_fnames())
        if (withValue == name && longNames.size() > 1) return name;
  return longNames.front();
}

void writeSlicerParameter(std::ostream& xml, const CLI::Option& option, int& index) {
  const std::string longName = slicerLongName(option);
  const std::string name = longName.empty() ? option.get_name() : longName;
  const SlicerParameterXml p = slicerParameterXml(option, longName);
  xml << "    <" << p.tag << p.attributes << ">\n";
  xml << "      <name>" << slicerName(name) << "</name>\n";
  // A positional argument has an index instead of a flag (the parser refuses both).
  if (longName.empty())
    xml << "      <index>" << index++ << "</index>\n";
  else
    xml << "      <longflag>" << slicerName(longName) << "</longflag>\n";
  xml << "      <label>" << xmlEscaped(slicerLabel(name)) << "</label>\n";
  xml << "      <description>" << xmlEscaped(option.get_description()) << "</description>\n";
  if (!p.defaultValue.empty()) xml << "      <default>" << xmlEscaped(p.defaultValue) << "</default>\n";
  if (p.channel) xml << "      <channel>" << (p.output ? "output" : "input") << "</channel>\n";
  for (const std::string& element : p.elements) xml << "      <element>" << xmlEscaped(element) << "</element>\n";
  xml << "    </" << p.tag << ">\n";
}

bool isInputOrOutput(const CLI::Option& option) {
  const auto annotated = slicerAnnotations().find(&option);
  if (annotated != slicerAnnotations().end()) return true;
  if (option.get_expected_max() == 0 || !enumerationElements(option).empty()) return false;
  const std::string type = option.get_type_name().substr(0, option.get_type_name().find(':'));
  if (type == "INT" || type == "UINT" || type == "FLOAT") return false;
  const std::string longName = slicerLongName(option);
  if (longName.empty()) return true;
  const std::string flag = "--" + longName;
  return flag == "--scan" || flag == "--labels" || flag == "--organs" || (isOutputOption(flag) && flag != "--report");
}

}  // namespace

CLI::Option* slicerParameter(CLI::Option* option, SlicerKind kind, bool output, const std::string& fileExtensions) {
  slicerAnnotations()[option] = SlicerAnnotation{kind, output, fileExtensions};
  return option;
}

std::string slicerXml(const CLI::App& command) {
  std::vector<const CLI::Option*> io, settings;
  for (const CLI::Option* option : command.get_options()) {
    const std::string name = option->get_name();
    if (name == "--help" || name == "--xml") continue;
    (isInputOrOutput(*option) ? io : settings).push_back(option);
  }
  std::ostringstream xml;
  xml << "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n<executable>\n";
  xml << "  <category>Vesalius</category>\n";
  std::string title = command.get_name();  // "markers convert": the path below the program
  for (const CLI::App* parent = command.get_parent(); parent && parent->get_parent(); parent = parent->get_parent())
    title = parent->get_name() + " " + title;
  xml << "  <title>Vesalius " << xmlEscaped(title) << "</title>\n";
  xml << "  <description>" << xmlEscaped(command.get_description()) << "</description>\n";
  xml << "  <version>" << VESALIUS_VERSION << "</version>\n";
  xml << "  <documentation-url></documentation-url>\n  <license></license>\n";
  xml << "  <contributor>Vesalius</contributor>\n";
  int index = 0;
  const auto group = [&](const char* label, const char* description, const std::vector<const CLI::Option*>& options) {
    if (options.empty()) return;
    xml << "  <parameters>\n    <label>" << label << "</label>\n    <description>" << description
        << "</description>\n";
    for (const CLI::Option* option : options) writeSlicerParameter(xml, *option, index);
    xml << "  </parameters>\n";
  };
  group("Inputs and outputs", "What the command reads and writes", io);
  group("Settings", "How the command works", settings);
  xml << "</executable>\n";
  return xml.str();
}

void slicerArguments(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    char* arg = argv[i];
    if (std::strncmp(arg, "--", 2) != 0) continue;
    if (arg[2] == '\0') break;  // "--": what follows are values
    for (char* c = arg + 2; *c != '\0' && *c != '='; ++c)
      if (*c == '_') *c = '-';
  }
}

void addCommonOptions(CLI::App& command, CommonOptions& options) {
  command.add_option("--progress", options.progress, "Progress display: none, bar, slicer (3D Slicer CLI), auto")
      ->check(CLI::IsMember({"none", "bar", "slicer", "auto"}))
      ->capture_default_str();
  command.add_flag("--force", options.force, "Replace output files that already exist");
  command.add_option("--report", options.report, "Write a JSON report (inputs, parameters, stage times, metrics)");
  // Run as the flag is read, before CLI11 checks the required options; CLI::Success exits 0 in main.
  command
      .add_flag_callback(
          "--xml",
          [&command] {
            std::cout << slicerXml(command);
            throw CLI::Success();
          },
          "Print the command's 3D Slicer CLI module description (XML) and exit")
      ->trigger_on_parse();
  // Refused before the work, not after it: the report is written last.
  command.parse_complete_callback([&command, &options] {
    checkInputsAndOutputs(command);
    if (!options.report.empty() && !options.force && std::filesystem::exists(options.report))
      throw UsageError(options.report + ": exists; pass --force to replace it");
  });
}

std::string errorMessage(const Error& error) {
  const auto* badInput = dynamic_cast<const BadInput*>(&error);
  if (!badInput || !badInput->file().empty() || commandInputs().empty()) return error.what();
  std::string files;
  for (const std::string& input : commandInputs()) files += (files.empty() ? "" : ", ") + input;
  return files + ": " + badInput->problem();
}

Label resolveLabel(const LabelMap& map, const std::string& idOrName, const std::string& labelsPath) {
  try {
    return map.table.resolve(idOrName);
  } catch (const UsageError&) {
    throw UsageError(labelsPath + ": no label '" + idOrName + "' (neither an id nor a name in its label table)");
  }
}

void warnIfOverTetTarget(long tets, long targetTets, const std::string& option) {
  if (tets <= 2 * targetTets) return;
  std::cerr << "vesalius: warning: the rig has " << tets << " tets, more than twice the " << targetTets << " of "
            << option << ": its body and bone surfaces could not be coarsened to their budgets\n";
}

}  // namespace vesalius::cli
