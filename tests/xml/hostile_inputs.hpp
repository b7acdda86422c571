// The hostile world XML of hostile_test.cpp, shared with its benchmark
// (bench/xml/hostile.cpp): the test asserts what each input is refused
// with, the benchmark times the same inputs, so neither drifts.
#pragma once
#include <filesystem>
#include <fstream>
#include <string>

namespace rscene::xml::hostile {

// Nine levels of entities, each ten of the one below: 10^9 "lol"s if a
// parser expanded them.
inline std::string billionLaughs() {
  std::string xml = "<?xml version=\"1.0\"?>\n<!DOCTYPE raisim [\n  <!ENTITY lol \"lol\">\n";
  for (int i = 1; i <= 9; ++i) {
    xml += "  <!ENTITY lol" + std::to_string(i) + " \"";
    for (int k = 0; k < 10; ++k) xml += "&lol" + (i == 1 ? std::string() : std::to_string(i - 1)) + ";";
    xml += "\">\n";
  }
  return xml + "]>\n<raisim><objects><sphere name=\"&lol9;\"/></objects></raisim>\n";
}

// <raisim> and n nested <a> elements, on one line.
inline std::string deepNesting(int n) {
  std::string xml = "<raisim>";
  for (int i = 0; i < n; ++i) xml += "<a>";
  for (int i = 0; i < n; ++i) xml += "</a>";
  return xml + "</raisim>";
}

// One array of 10^9 iterations, the <array> on line 2.
inline std::string billionLoop() {
  return "<raisim><objects>\n<array idx=\"@@i\" start=\"0\" end=\"1000000000\" increment=\"1\"><sphere/></array>"
         "</objects></raisim>";
}

// 10^4 x 10^4 iterations, each making a sphere and its <dim>.
inline std::string nestedLoops() {
  return "<raisim><objects><array idx=\"@@i\" start=\"0\" end=\"10000\" increment=\"1\">"
         "<array idx=\"@@j\" start=\"0\" end=\"10000\" increment=\"1\"><sphere name=\"s@@i_@@j\"><dim radius=\"1\"/>"
         "</sphere></array></array></objects></raisim>";
}

// 10^5 iterations of a body holding 1000 loops that run zero times: no
// element made, 10^8 loops entered.
inline std::string manyEmptyLoops() {
  std::string body;
  for (int i = 0; i < 1000; ++i) body += "<array idx=\"@@j\" start=\"0\" end=\"0\" increment=\"1\"><box/></array>";
  return "<raisim><objects><array idx=\"@@i\" start=\"0\" end=\"100000\" increment=\"1\">" + body +
         "</array></objects></raisim>";
}

// A box named @@p0 where each parameter is the next one twice and the
// last is `last`: 2^levels copies of it if nothing stopped the doubling.
inline std::string parameterDoubling(int levels, const std::string& last) {
  std::string params;
  for (int i = 0; i < levels; ++i)
    params += "<p" + std::to_string(i) + " value=\"@@p" + std::to_string(i + 1) + "@@p" + std::to_string(i + 1) + "\"/>";
  params += "<p" + std::to_string(levels) + " value=\"" + last + "\"/>";
  return "<raisim><params>" + params + "</params><objects><box name=\"@@p0\"/></objects></raisim>";
}

// Writes l0.xml .. l12.xml into dir, each level including the next ten
// times (10^12 reads of l12.xml's sphere without a bound); returns l0.xml.
inline std::filesystem::path writeIncludeDiamond(const std::filesystem::path& dir) {
  for (int i = 0; i < 12; ++i) {
    std::string xml = "<raisim>";
    for (int k = 0; k < 10; ++k) xml += "<include file=\"l" + std::to_string(i + 1) + ".xml\"/>";
    std::ofstream(dir / ("l" + std::to_string(i) + ".xml")) << xml + "</raisim>";
  }
  std::ofstream(dir / "l12.xml") << "<raisim><objects><sphere/></objects></raisim>";
  return dir / "l0.xml";
}

}  // namespace rscene::xml::hostile
