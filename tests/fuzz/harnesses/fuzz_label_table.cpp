#include "fuzz_common.h"
#include "vesalius/io/label_table_io.h"

// Any table read must read back from each format we write it in, with its entries; a name a format cannot
// carry (a tab in our TSV) is refused by that writer with a BadInput.
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace vesalius;
  return fuzz::fuzzOne(
      data, size, [](std::string_view text) { return io::parseLabelTable(text, "fuzz.txt"); },
      [](const LabelTable& table) {
        for (auto format : {io::formatLabelTable, io::formatSlicerColorTable, io::formatItkSnapLabels}) {
          std::string text;
          try {
            text = format(table);
          } catch (const BadInput&) {
            continue;
          }
          if (io::parseLabelTable(text, "roundtrip.txt").entries.size() != table.entries.size()) return false;
        }
        return true;
      });
}
