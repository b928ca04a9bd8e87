// `vesalius COMMAND --xml`: the 3D Slicer CLI module description of each command a Slicer user would run,
// parsed with VTK's XML parser and held to SlicerExecutionModel's rules (ModuleDescriptionParser.cxx:
// <executable> outermost, parameters inside <parameters>, <name> and <longflag> of letters, digits and '_',
// no <index> beside a flag, channel input or output on images, geometries and files). Each parameter is
// compared with the option `--help` lists for the command: one per option, long flag and type matching.
#include "run_command.h"

#include <vtkNew.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <regex>
#include <set>
#include <sstream>

namespace vesalius::test {
namespace {

namespace fs = std::filesystem;

// An option as `vesalius COMMAND --help` shows it.
struct HelpOption {
  std::string name;  // "skin-thickness", or a positional's name
  bool positional = false, flag = false;
  std::string type;  // "TEXT", "INT", "FLOAT", "UINT"; empty for a flag
  std::vector<std::string> members;  // of an IsMember check
};

std::vector<HelpOption> helpOptions(const std::string& help) {
  std::vector<HelpOption> options;
  std::istringstream lines(help);
  bool positionals = false;
  // "  --name TYPE..." or "  -h,--name   description" or, under Positionals:, "  name TYPE ...".
  // "--cor-centres,--no-cor-centres{false}": a flag with a negated name, which Slicer's check box passes.
  const std::regex optionLine(
      R"(^  (?:-\w,)?--((?:[\w-]+)(?:\{\w+\})?(?:,--[\w-]+(?:\{\w+\})?)*)(?: ([A-Z]+)(?::\{([^}]*)\})?)?(?:[ =:].*)?$)");
  const std::regex negatedName(R"(--([\w-]+)\{false\})");
  const std::regex positionalLine(R"(^  ([\w-]+) ([A-Z]+)\b.*)");
  for (std::string line; std::getline(lines, line);) {
    if (line == "Positionals:") positionals = true;
    if (line == "Options:") positionals = false;
    std::smatch m;
    if (positionals && std::regex_match(line, m, positionalLine)) {
      options.push_back({m[1], true, false, m[2], {}});
    } else if (!positionals && std::regex_match(line, m, optionLine)) {
      const std::string names = m[1];
      std::smatch negated;
      const bool hasNegated = names.find(',') != std::string::npos && std::regex_search(names, negated, negatedName);
      HelpOption option{hasNegated ? negated[1].str() : names.substr(0, names.find_first_of(",{")), false,
                        !m[2].matched, m[2], {}};
      std::stringstream members(m[3].str());
      for (std::string member; std::getline(members, member, ',');) option.members.push_back(member);
      if (option.name != "help" && option.name != "xml") options.push_back(option);
    }
  }
  return options;
}

std::string slicerName(std::string name) {
  std::replace(name.begin(), name.end(), '-', '_');
  return name;
}

bool validVariable(const std::string& s) {
  return std::regex_match(s, std::regex("[A-Za-z_][A-Za-z0-9_]*"));
}

std::string childText(vtkXMLDataElement* element, const char* name) {
  vtkXMLDataElement* child = element->FindNestedElementWithName(name);
  if (!child || !child->GetCharacterData()) return {};
  std::string text = child->GetCharacterData();
  const auto first = text.find_first_not_of(" \n\t"), last = text.find_last_not_of(" \n\t");
  return first == std::string::npos ? std::string() : text.substr(first, last - first + 1);
}

struct Parameter {
  std::string tag, name, longflag, index, channel, defaultValue, type;
  std::vector<std::string> elements;
};

// The command's XML, parsed; fails the test on a parse error or a broken SlicerExecutionModel rule.
std::vector<Parameter> slicerParameters(const std::vector<std::string>& command, std::string& title) {
  std::vector<std::string> args = command;
  args.push_back("--xml");
  const CommandResult r = runVesalius(args);
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  std::string file = "xml";
  for (const std::string& word : command) file += "_" + word;
  const fs::path path = fs::path(outputDir()) / (file + ".xml");
  std::ofstream(path) << r.out;

  vtkNew<vtkXMLDataParser> parser;
  parser->SetFileName(path.c_str());
  std::vector<Parameter> parameters;
  if (!parser->Parse()) {
    ADD_FAILURE() << path << ": not well-formed XML";
    return parameters;
  }
  vtkXMLDataElement* root = parser->GetRootElement();
  EXPECT_STREQ(root->GetName(), "executable");
  title = childText(root, "title");
  EXPECT_FALSE(childText(root, "description").empty());
  EXPECT_FALSE(childText(root, "version").empty());
  const std::set<std::string> kChannelTags = {"image", "geometry", "file", "transform", "table", "measurement"};
  std::set<std::string> names;
  for (int g = 0; g < root->GetNumberOfNestedElements(); ++g) {
    vtkXMLDataElement* group = root->GetNestedElement(g);
    if (std::string(group->GetName()) != "parameters") continue;
    EXPECT_FALSE(childText(group, "label").empty());
    for (int i = 0; i < group->GetNumberOfNestedElements(); ++i) {
      vtkXMLDataElement* e = group->GetNestedElement(i);
      const std::string tag = e->GetName();
      if (tag == "label" || tag == "description") continue;
      Parameter p{tag, childText(e, "name"), childText(e, "longflag"), childText(e, "index"), childText(e, "channel"),
                  childText(e, "default"), e->GetAttribute("type") ? e->GetAttribute("type") : "", {}};
      for (int k = 0; k < e->GetNumberOfNestedElements(); ++k)
        if (std::string(e->GetNestedElement(k)->GetName()) == "element")
          p.elements.push_back(e->GetNestedElement(k)->GetCharacterData());
      EXPECT_TRUE(validVariable(p.name)) << tag << " <name> '" << p.name << "'";
      EXPECT_TRUE(names.insert(p.name).second) << "two parameters named " << p.name;
      EXPECT_NE(p.longflag.empty(), p.index.empty()) << p.name << ": a <longflag> or an <index>, not both";
      if (!p.longflag.empty()) {
        EXPECT_TRUE(validVariable(p.longflag)) << "<longflag> '" << p.longflag << "'";
      }
      if (kChannelTags.count(tag))
        EXPECT_TRUE(p.channel == "input" || p.channel == "output") << p.name << " channel '" << p.channel << "'";
      else
        EXPECT_TRUE(p.channel.empty()) << p.name << ": <" << tag << "> takes no channel";
      if (tag == "string-enumeration") {
        EXPECT_FALSE(p.elements.empty()) << p.name;
        EXPECT_NE(std::find(p.elements.begin(), p.elements.end(), p.defaultValue), p.elements.end())
            << p.name << " default '" << p.defaultValue << "' is not an element";
      }
      parameters.push_back(p);
    }
  }
  return parameters;
}

// The Slicer tags a --help option of each type may become.
bool typeMatches(const HelpOption& option, const Parameter& p) {
  if (option.flag) return p.tag == "boolean" && p.defaultValue == "false";
  if (!option.members.empty()) return p.tag == "string-enumeration" && p.elements == option.members;
  if (option.type == "INT" || option.type == "UINT") return p.tag == "integer";
  if (option.type == "FLOAT") return p.tag == "double";
  static const std::set<std::string> kText = {"string", "image", "geometry", "file", "directory"};
  return option.type == "TEXT" && kText.count(p.tag) == 1;
}

const std::vector<std::vector<std::string>> kCommands = {
    {"segment"}, {"surface"},        {"tetmesh"},          {"markers", "sample"}, {"markers", "suggest"},
    {"fit"},     {"fat", "forest"},  {"transfer"},         {"patient"},           {"pose"},
    {"labels", "fill"},  {"rig"},            {"markers", "convert"}};

TEST(CliSlicerXml, EveryOptionIsOneParameterWithItsFlagAndType) {
  for (const std::vector<std::string>& command : kCommands) {
    std::string name;
    for (const std::string& word : command) name += (name.empty() ? "" : " ") + word;
    SCOPED_TRACE(name);
    std::vector<std::string> helpArgs = command;
    helpArgs.push_back("--help");
    const CommandResult help = runVesalius(helpArgs);
    ASSERT_EQ(help.exitCode, 0) << help.err;
    const std::vector<HelpOption> options = helpOptions(help.out);
    ASSERT_FALSE(options.empty()) << help.out;

    std::string title;
    const std::vector<Parameter> parameters = slicerParameters(command, title);
    EXPECT_EQ(title, "Vesalius " + name);
    std::cout << name << ": " << options.size() << " options, " << parameters.size() << " parameters\n";
    EXPECT_EQ(parameters.size(), options.size());
    int positional = 0;
    for (const HelpOption& option : options) {
      const auto p = std::find_if(parameters.begin(), parameters.end(),
                                  [&](const Parameter& p) { return p.name == slicerName(option.name); });
      if (p == parameters.end()) {
        ADD_FAILURE() << "no parameter for " << option.name;
        continue;
      }
      if (option.positional)
        EXPECT_EQ(p->index, std::to_string(positional++)) << option.name;
      else
        EXPECT_EQ(p->longflag, slicerName(option.name));
      EXPECT_TRUE(typeMatches(option, *p)) << option.name << " (" << (option.flag ? "flag" : option.type)
                                           << ") became <" << p->tag << ">";
      if (option.name == "progress") {
        EXPECT_EQ(p->defaultValue, "slicer");
      }
    }
  }
}

const Parameter* find(const std::vector<Parameter>& parameters, const std::string& name) {
  for (const Parameter& p : parameters)
    if (p.name == name) return &p;
  return nullptr;
}

TEST(CliSlicerXml, ImagesAndModelsHaveTheirChannels) {
  std::string title;
  const std::vector<Parameter> segment = slicerParameters({"segment"}, title);
  const Parameter* scan = find(segment, "scan");
  const Parameter* out = find(segment, "out");
  ASSERT_TRUE(scan && out);
  EXPECT_EQ(scan->tag, "image");
  EXPECT_EQ(scan->channel, "input");
  EXPECT_EQ(out->tag, "image");
  EXPECT_EQ(out->type, "label");
  EXPECT_EQ(out->channel, "output");

  const std::vector<Parameter> surface = slicerParameters({"surface"}, title);
  const Parameter* labels = find(surface, "labels");
  const Parameter* mesh = find(surface, "out");
  ASSERT_TRUE(labels && mesh);
  EXPECT_EQ(labels->tag, "image");
  EXPECT_EQ(labels->type, "label");
  EXPECT_EQ(labels->channel, "input");
  EXPECT_EQ(mesh->tag, "geometry");
  EXPECT_EQ(mesh->channel, "output");
  // The scan an RT Structure Set given as --labels is read onto.
  const Parameter* grid = find(surface, "grid");
  ASSERT_TRUE(grid);
  EXPECT_EQ(grid->tag, "image");
  EXPECT_EQ(grid->channel, "input");

  // The patient's output is a folder; its scan and organ labels are volumes.
  const std::vector<Parameter> patient = slicerParameters({"patient"}, title);
  const Parameter* ct = find(patient, "scan");
  const Parameter* organs = find(patient, "organs");
  const Parameter* folder = find(patient, "out");
  ASSERT_TRUE(ct && organs && folder);
  EXPECT_EQ(ct->tag, "image");
  EXPECT_EQ(ct->channel, "input");
  EXPECT_EQ(organs->type, "label");
  EXPECT_EQ(folder->tag, "directory");
}

// Slicer passes the <longflag>s: --skin_thickness reaches --skin-thickness (its value checked, so refused
// here), and a value with '_' in it is not changed.
TEST(CliSlicerXml, SlicerFlagsReachTheOptions) {
  const std::string missing = (fs::path(outputDir()) / "no_such_scan.nii.gz").string();
  CommandResult r = runVesalius({"segment", "--scan", missing, "--out", "x.nii.gz", "--skin_thickness", "thick"});
  EXPECT_EQ(r.exitCode, 2) << r.err;
  expectContains(r.err, "--skin-thickness");
  r = runVesalius({"segment", "--scan", missing, "--out=" + outputDir() + "/out_labels.nii.gz", "--skin_thickness=1.5"});
  EXPECT_EQ(r.exitCode, 3) << r.err;
  expectContains(r.err, "no_such_scan.nii.gz");
}

}  // namespace
}  // namespace vesalius::test
