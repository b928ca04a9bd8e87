// Biovision hierarchy (BVH) motions. See motion_io.h.
#include "vesalius/io/motion_io.h"

#include "vesalius/core/error.h"
#include "vesalius/io/text_file.h"

#include <algorithm>
#include <cctype>
#include <charconv>

namespace vesalius::io {

namespace {

// Deeper hierarchies are not skeletons but attacks on the recursion.
constexpr int kMaxDepth = 1000;

constexpr const char* kChannelNames[] = {"Xposition", "Yposition", "Zposition", "Xrotation", "Yrotation", "Zrotation"};

// Whitespace tokens across lines; errors name the line of the current token.
class Tokens {
 public:
  explicit Tokens(LineReader& reader) : reader_(reader) {}

  // The next token, or an empty view at the end of the text.
  std::string_view next() {
    while (index_ >= tokens_.size()) {
      std::string_view line;
      if (!reader_.next(line)) return {};
      tokens_ = splitWhitespace(line);
      index_ = 0;
    }
    return tokens_[index_++];
  }
  std::string_view expect(const char* what) {
    std::string_view t = next();
    if (t.empty()) fail(std::string("file ends where ") + what + " should be");
    return t;
  }
  void expectWord(std::string_view word) {
    std::string_view t = expect(std::string(word).c_str());
    if (t != word) fail("expected '" + std::string(word) + "', found '" + std::string(t) + "'");
  }
  double number(const char* what) { return parseDouble(expect(what), reader_, what); }
  bool lineDone() const { return index_ >= tokens_.size(); }
  [[noreturn]] void fail(const std::string& problem) const { reader_.fail(problem); }
  LineReader& reader() { return reader_; }

 private:
  LineReader& reader_;
  std::vector<std::string_view> tokens_;
  std::size_t index_ = 0;
};

bool equalsIgnoringCase(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

std::vector<Channel> readChannels(Tokens& t) {
  const long long count = parseInteger(t.expect("a channel count"), t.reader(), "channel count");
  if (count < 0 || count > 6) t.fail("CHANNELS " + std::to_string(count) + ": a joint has 0 to 6 channels");
  std::vector<Channel> channels;
  for (long long i = 0; i < count; ++i) {
    const std::string_view name = t.expect("a channel name");
    const auto* found = std::find_if(std::begin(kChannelNames), std::end(kChannelNames),
                                     [&](const char* n) { return equalsIgnoringCase(name, n); });
    if (found == std::end(kChannelNames))
      t.fail("unknown channel '" + std::string(name) + "' (Xposition ... Zrotation)");
    const Channel c = Channel(found - std::begin(kChannelNames));
    if (std::find(channels.begin(), channels.end(), c) != channels.end())
      t.fail("channel " + std::string(name) + " appears twice");
    channels.push_back(c);
  }
  return channels;
}

Eigen::Vector3d readOffset(Tokens& t) {
  t.expectWord("OFFSET");
  Eigen::Vector3d p;
  for (int i = 0; i < 3; ++i) p[i] = t.number("offset");
  return p;
}

Eigen::Vector3d readEndSite(Tokens& t) {
  t.expectWord("Site");
  t.expectWord("{");
  const Eigen::Vector3d tail = readOffset(t);
  t.expectWord("}");
  return tail;
}

void readJoint(Tokens& t, Motion& motion, int parent, int depth) {
  if (depth > kMaxDepth) t.fail("joints nested more than " + std::to_string(kMaxDepth) + " deep");
  const std::string name(t.expect("a joint name"));
  if (name == "{") t.fail("a joint without a name");
  const int index = int(motion.skeleton.joints.size());
  motion.skeleton.joints.push_back(Joint{name, parent, Eigen::Isometry3d::Identity(), Eigen::Vector3d::Zero()});
  motion.channels.emplace_back();
  t.expectWord("{");
  motion.skeleton.joints[std::size_t(index)].restLocal.translation() = readOffset(t);
  bool haveChannels = false, haveEndSite = false;
  for (;;) {
    const std::string_view token = t.expect("JOINT, End Site or '}'");
    if (token == "}") return;
    if (token == "CHANNELS" && !haveChannels) {
      motion.channels[std::size_t(index)] = readChannels(t);
      haveChannels = true;
    } else if (token == "JOINT") {
      readJoint(t, motion, index, depth + 1);
    } else if (token == "End" && !haveEndSite) {
      motion.skeleton.joints[std::size_t(index)].tail = readEndSite(t);
      haveEndSite = true;
    } else {
      t.fail("unexpected '" + std::string(token) + "' in joint " + name);
    }
  }
}

void readHierarchy(Tokens& t, Motion& motion) {
  const std::string_view first = t.next();
  if (first != "HIERARCHY") t.fail("not a BVH file: it does not start with HIERARCHY");
  for (;;) {
    const std::string_view token = t.next();
    if (token.empty()) t.fail("no MOTION section");
    if (token == "MOTION") break;
    if (token != "ROOT") t.fail("expected ROOT or MOTION, found '" + std::string(token) + "'");
    readJoint(t, motion, -1, 0);
  }
  if (motion.skeleton.joints.empty()) t.fail("MOTION before any ROOT joint");
}

// "Frames: N" and "Frame Time: t"; leaves the reader at the end of the Frame Time line.
int readMotionHeader(Tokens& t, Motion& motion, std::size_t textSize) {
  t.expectWord("Frames:");
  const long long frames = parseInteger(t.expect("the frame count"), t.reader(), "frame count");
  // Each frame needs at least one character and a line break; larger counts can only be lies.
  if (frames < 0 || std::size_t(frames) > textSize) t.fail("impossible frame count " + std::to_string(frames));
  t.expectWord("Frame");
  t.expectWord("Time:");
  motion.frameTime = t.number("frame time");
  if (motion.frameTime <= 0) t.fail("the frame time must be positive");
  if (!t.lineDone()) t.fail("unexpected text after the frame time");
  return int(frames);
}

// Exported motion often disagrees with its own "Frames:" line by a frame or two. Frame lines beyond the
// declared count are not read (the declared count is kept); fewer lines than declared give the frames
// present. Either way `warning` gets one line saying so; a frame line with a wrong value count is still
// refused, since it is a broken frame, not a miscount.
void readFrames(LineReader& reader, Motion& motion, int frames, std::string* warning) {
  int columns = 0;
  for (const auto& c : motion.channels) columns += int(c.size());
  motion.values.setZero(frames, columns);
  std::string_view line;
  int frame = 0, extra = 0, firstExtraLine = 0;
  while (reader.next(line)) {
    const std::vector<std::string_view> tokens = splitWhitespace(line);
    if (tokens.empty()) continue;
    if (frame == frames) {
      if (extra++ == 0) firstExtraLine = reader.lineNumber();
      continue;
    }
    if (int(tokens.size()) != columns)
      reader.fail("frame " + std::to_string(frame + 1) + " has " + std::to_string(tokens.size()) +
                  " values, the hierarchy has " + std::to_string(columns) + " channels");
    for (int c = 0; c < columns; ++c) motion.values(frame, c) = parseDouble(tokens[std::size_t(c)], reader, "value");
    ++frame;
  }
  const std::string declared = "'Frames: " + std::to_string(frames) + "'";
  std::string note;
  if (extra > 0)
    note = reader.source() + ": line " + std::to_string(firstExtraLine) + ": " + std::to_string(extra) +
           " frame line" + (extra > 1 ? "s" : "") + " beyond " + declared + " not read";
  if (frame < frames && columns > 0) {
    motion.values.conservativeResize(frame, columns);
    note = reader.source() + ": " + std::to_string(frame) + " frame lines for " + declared + "; the " +
           std::to_string(frame) + " present are read";
  }
  if (!note.empty() && warning) *warning = note;
}

}  // namespace

Motion parseBvh(std::string_view text, const std::string& source, std::string* warning) {
  if (warning) warning->clear();
  LineReader reader(text, source);
  Tokens tokens(reader);
  Motion motion;
  readHierarchy(tokens, motion);
  const int frames = readMotionHeader(tokens, motion, text.size());
  readFrames(reader, motion, frames, warning);
  motion.skeleton.validate(source);
  return motion;
}

Motion readBvh(const std::string& path, std::string* warning) { return parseBvh(readTextFile(path), path, warning); }

Motion readBvh(const std::string& path, std::ostream& warnings) {
  std::string warning;
  Motion motion = readBvh(path, &warning);
  if (!warning.empty()) warnings << "warning: " << warning << '\n';
  return motion;
}

// ---- writing ----

namespace {

std::string number(double value) {
  char buffer[32];
  return std::string(buffer, std::to_chars(buffer, buffer + sizeof buffer, value).ptr);
}

std::string vectorText(const Eigen::Vector3d& v) { return number(v.x()) + " " + number(v.y()) + " " + number(v.z()); }

void checkWritable(const Motion& motion) {
  const auto& joints = motion.skeleton.joints;
  if (motion.channels.size() != joints.size())
    throw UsageError("BVH: " + std::to_string(motion.channels.size()) + " channel lists for " +
                     std::to_string(joints.size()) + " joints");
  std::size_t columns = 0;
  for (const auto& c : motion.channels) columns += c.size();
  if (std::size_t(motion.values.cols()) != columns)
    throw UsageError("BVH: " + std::to_string(motion.values.cols()) + " value columns for " + std::to_string(columns) +
                     " channels");
  for (std::size_t j = 0; j < joints.size(); ++j) {
    const Joint& joint = joints[j];
    if (joint.name.empty() ||
        std::any_of(joint.name.begin(), joint.name.end(), [](unsigned char c) { return std::isspace(c); }))
      throw UsageError("BVH: joint name '" + joint.name + "' is empty or holds spaces");
    if (joint.parent >= int(j) || joint.parent < -1)
      throw UsageError("BVH: joint " + joint.name + " comes before its parent");
    if (!joint.restLocal.linear().isIdentity(1e-12))
      throw UsageError("BVH: joint " + joint.name + " has a rest rotation, which BVH offsets cannot hold");
  }
}

struct Writer {
  const Motion& motion;
  std::vector<std::vector<int>> children;
  std::vector<int> firstColumn;  // of each joint's channels in motion.values
  std::vector<int> order;        // joints in the order written
  std::string out;

  void joint(int j, int depth) {
    const Joint& joint = motion.skeleton.joints[std::size_t(j)];
    const std::string pad(std::size_t(depth), '\t');
    out += pad + (joint.parent < 0 ? "ROOT " : "JOINT ") + joint.name + "\n" + pad + "{\n";
    out += pad + "\tOFFSET " + vectorText(joint.restLocal.translation()) + "\n";
    const auto& channels = motion.channels[std::size_t(j)];
    out += pad + "\tCHANNELS " + std::to_string(channels.size());
    for (Channel c : channels) out += std::string(" ") + kChannelNames[int(c)];
    out += "\n";
    order.push_back(j);
    for (int child : children[std::size_t(j)]) this->joint(child, depth + 1);
    if (children[std::size_t(j)].empty() || !joint.tail.isZero(0.0))
      out += pad + "\tEnd Site\n" + pad + "\t{\n" + pad + "\t\tOFFSET " + vectorText(joint.tail) + "\n" + pad + "\t}\n";
    out += pad + "}\n";
  }

  void frames() {
    out +=
        "MOTION\nFrames: " + std::to_string(motion.values.rows()) + "\nFrame Time: " + number(motion.frameTime) + "\n";
    for (Eigen::Index f = 0; f < motion.values.rows(); ++f) {
      std::string line;
      for (int j : order)
        for (std::size_t c = 0; c < motion.channels[std::size_t(j)].size(); ++c)
          line += (line.empty() ? "" : " ") + number(motion.values(f, firstColumn[std::size_t(j)] + int(c)));
      out += line + "\n";
    }
  }
};

}  // namespace

std::string formatBvh(const Motion& motion) {
  checkWritable(motion);
  Writer w{motion, {}, {}, {}, "HIERARCHY\n"};
  const auto& joints = motion.skeleton.joints;
  w.children.resize(joints.size());
  int column = 0;
  for (std::size_t j = 0; j < joints.size(); ++j) {
    if (joints[j].parent >= 0) w.children[std::size_t(joints[j].parent)].push_back(int(j));
    w.firstColumn.push_back(column);
    column += int(motion.channels[j].size());
  }
  for (std::size_t j = 0; j < joints.size(); ++j)
    if (joints[j].parent < 0) w.joint(int(j), 0);
  w.frames();
  return w.out;
}

void writeBvh(const std::string& path, const Motion& motion, const WriteOptions& options) {
  const std::string text = formatBvh(motion);
  writeAtomically(path, options, [&](const std::string& temporaryPath) { writeFileBytes(temporaryPath, text); });
}

}  // namespace vesalius::io
