#include "accuracy/pareto_chart.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace xshade::accuracy {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::IsEmpty;
using ::testing::Not;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// ---- a small XML reader: enough of XML 1.0 to check that a document is well-formed (one root,
// every element closed in order, quoted and unique attributes, only known entity references) and
// to look at its elements.

struct Element {
  std::string name;
  std::map<std::string, std::string> attributes;
  std::string text;  // the decoded character data directly inside it
  size_t parent = SIZE_MAX;
  double number(const std::string& attribute) const { return std::stod(attributes.at(attribute)); }
};

struct Xml {
  std::vector<Element> elements;  // in document order
  std::string error;              // empty when well-formed
};

bool name_char(char c, bool first) {
  const bool letter = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_' || c == ':';
  return letter || (!first && ((c >= '0' && c <= '9') || c == '-' || c == '.'));
}

// Decodes character data; false on a bare '&', an unknown entity or a '<'.
bool decode(std::string_view raw, std::string& out) {
  for (size_t i = 0; i < raw.size(); ++i) {
    if (raw[i] == '<') return false;
    if (raw[i] != '&') {
      out += raw[i];
      continue;
    }
    const size_t semicolon = raw.find(';', i);
    if (semicolon == std::string_view::npos) return false;
    const std::string_view entity = raw.substr(i + 1, semicolon - i - 1);
    static const std::map<std::string_view, char> named = {
        {"amp", '&'}, {"lt", '<'}, {"gt", '>'}, {"quot", '"'}, {"apos", '\''}};
    if (auto it = named.find(entity); it != named.end()) {
      out += it->second;
    } else if (entity.size() > 1 && entity[0] == '#') {
      // A character reference, decimal or hexadecimal, written back as UTF-8.
      const bool hex = entity[1] == 'x';
      const std::string digits(entity.substr(hex ? 2 : 1));
      if (digits.empty() ||
          digits.find_first_not_of(hex ? "0123456789abcdefABCDEF" : "0123456789") != std::string::npos)
        return false;
      const unsigned long code = std::stoul(digits, nullptr, hex ? 16 : 10);
      if (code < 0x80) {
        out += char(code);
      } else if (code < 0x800) {
        out += char(0xC0 | (code >> 6));
        out += char(0x80 | (code & 0x3F));
      } else if (code < 0x10000) {
        out += char(0xE0 | (code >> 12));
        out += char(0x80 | ((code >> 6) & 0x3F));
        out += char(0x80 | (code & 0x3F));
      } else {
        out += char(0xF0 | (code >> 18));
        out += char(0x80 | ((code >> 12) & 0x3F));
        out += char(0x80 | ((code >> 6) & 0x3F));
        out += char(0x80 | (code & 0x3F));
      }
    } else {
      return false;
    }
    i = semicolon;
  }
  return true;
}

Xml parse_xml(std::string_view doc) {
  Xml xml;
  std::vector<size_t> open;
  size_t roots = 0;
  size_t i = 0;
  const auto fail = [&](const std::string& why) {
    xml.error = why + " at byte " + std::to_string(i);
    return xml;
  };
  if (doc.substr(0, 5) == "<?xml") {
    i = doc.find("?>");
    if (i == std::string_view::npos) return fail("unterminated declaration");
    i += 2;
  }
  while (i < doc.size()) {
    if (doc[i] != '<') {
      const size_t end = std::min(doc.find('<', i), doc.size());
      const std::string_view raw = doc.substr(i, end - i);
      std::string text;
      if (!decode(raw, text)) return fail("bad character data");
      if (open.empty()) {
        if (text.find_first_not_of(" \t\r\n") != std::string::npos) return fail("text outside the root");
      } else {
        xml.elements[open.back()].text += text;
      }
      i = end;
      continue;
    }
    if (doc.substr(i, 4) == "<!--") {
      const size_t end = doc.find("-->", i);
      if (end == std::string_view::npos) return fail("unterminated comment");
      i = end + 3;
      continue;
    }
    if (doc.substr(i, 2) == "</") {
      size_t j = i + 2;
      while (j < doc.size() && name_char(doc[j], j == i + 2)) ++j;
      const std::string name(doc.substr(i + 2, j - i - 2));
      while (j < doc.size() && doc[j] == ' ') ++j;
      if (j >= doc.size() || doc[j] != '>') return fail("bad end tag");
      if (open.empty() || xml.elements[open.back()].name != name) return fail("end tag </" + name + "> does not match");
      open.pop_back();
      i = j + 1;
      continue;
    }
    // A start tag.
    size_t j = i + 1;
    if (j >= doc.size() || !name_char(doc[j], true)) return fail("bad tag name");
    while (j < doc.size() && name_char(doc[j], false)) ++j;
    Element element;
    element.name = std::string(doc.substr(i + 1, j - i - 1));
    element.parent = open.empty() ? SIZE_MAX : open.back();
    if (open.empty() && ++roots > 1) return fail("a second root");
    bool self_closing = false;
    for (;;) {
      const bool space = j < doc.size() && (doc[j] == ' ' || doc[j] == '\n' || doc[j] == '\t' || doc[j] == '\r');
      while (j < doc.size() && (doc[j] == ' ' || doc[j] == '\n' || doc[j] == '\t' || doc[j] == '\r')) ++j;
      if (j >= doc.size()) return fail("unterminated tag");
      if (doc[j] == '>') break;
      if (doc.substr(j, 2) == "/>") {
        self_closing = true;
        ++j;
        break;
      }
      if (!space || !name_char(doc[j], true)) return fail("bad attribute");
      const size_t name_start = j;
      while (j < doc.size() && name_char(doc[j], false)) ++j;
      const std::string name(doc.substr(name_start, j - name_start));
      if (j + 1 >= doc.size() || doc[j] != '=' || (doc[j + 1] != '"' && doc[j + 1] != '\''))
        return fail("bad attribute " + name);
      const char quote = doc[j + 1];
      const size_t value_end = doc.find(quote, j + 2);
      if (value_end == std::string_view::npos) return fail("unterminated attribute");
      std::string value;
      if (!decode(doc.substr(j + 2, value_end - j - 2), value)) return fail("bad attribute value of " + name);
      if (!element.attributes.emplace(name, value).second) return fail("duplicate attribute " + name);
      j = value_end + 1;
    }
    xml.elements.push_back(std::move(element));
    if (!self_closing) open.push_back(xml.elements.size() - 1);
    i = j + 1;
  }
  if (!open.empty()) return fail("<" + xml.elements[open.back()].name + "> is not closed");
  if (roots != 1) return fail("no root");
  return xml;
}

TEST(XmlReaderTest, RejectsWhatIsNotWellFormed) {
  EXPECT_EQ(parse_xml("<a><b/></a>").error, "");
  EXPECT_NE(parse_xml("<a><b></a>").error, "");
  EXPECT_NE(parse_xml("<a>").error, "");
  EXPECT_NE(parse_xml("<a x=1/>").error, "");
  EXPECT_NE(parse_xml("<a x=\"1\" x=\"2\"/>").error, "");
  EXPECT_NE(parse_xml("<a>x & y</a>").error, "");
  EXPECT_NE(parse_xml("<a>x <y</a>").error, "");
  EXPECT_NE(parse_xml("<a/><b/>").error, "");
  EXPECT_EQ(parse_xml("<a t=\"&lt;&amp;\">&quot;</a>").elements[0].attributes.at("t"), "<&");
}

// ---- helpers over a parsed chart ----

std::vector<const Element*> with_class(const Xml& xml, const std::string& cls) {
  std::vector<const Element*> found;
  for (const Element& e : xml.elements)
    if (auto it = e.attributes.find("class"); it != e.attributes.end() && it->second == cls) found.push_back(&e);
  return found;
}

// The tick label of an axis ("x-tick" or "y-tick") that reads `text`.
const Element* tick(const Xml& xml, const std::string& axis, const std::string& text) {
  for (const Element* e : with_class(xml, axis))
    if (e->text == text) return e;
  return nullptr;
}

// The marker of the point whose tooltip starts with `name` (series, label).
const Element* marker_of(const Xml& xml, const std::string& name) {
  for (size_t g = 0; g < xml.elements.size(); ++g) {
    const Element& group = xml.elements[g];
    if (group.name != "g" || group.attributes.count("class") == 0 || group.attributes.at("class") != "point") continue;
    bool match = false;
    for (const Element& e : xml.elements)
      if (e.parent == g && e.name == "title") match = e.text.rfind(name + ":", 0) == 0;
    if (!match) continue;
    for (const Element& e : xml.elements)
      if (e.parent == g && e.attributes.count("class") && e.attributes.at("class") == "marker") return &e;
  }
  return nullptr;
}

std::vector<std::pair<double, double>> polyline(const Element& e) {
  std::vector<std::pair<double, double>> vertices;
  std::istringstream in(e.attributes.at("points"));
  std::string pair;
  while (in >> pair) {
    const size_t comma = pair.find(',');
    vertices.emplace_back(std::stod(pair.substr(0, comma)), std::stod(pair.substr(comma + 1)));
  }
  return vertices;
}

std::vector<ChartSeries> three_lanes() {
  std::vector<ChartSeries> series;
  const std::vector<std::string> labels = {"16 samples", "22 samples", "43 samples", "71 samples", "reference"};
  const std::vector<double> base_ms = {5, 8, 15, 28, 50};
  const std::vector<double> errors = {1e-1, 2e-2, 3e-3, 1e-4, 0};
  const std::vector<std::string> lanes = {"gl", "vk", "vk-hlsl"};
  for (size_t l = 0; l < lanes.size(); ++l) {
    ChartSeries s{lanes[l], {}};
    for (size_t i = 0; i < labels.size(); ++i)
      s.points.push_back({labels[i], base_ms[i] * (1 + 0.08 * static_cast<double>(l)), base_ms[i] * 0.05,
                          errors[i] * (1 + 0.3 * static_cast<double>(l))});
    series.push_back(s);
  }
  return series;
}

// ---- pareto_front ----

TEST(ParetoFrontTest, LeavesOutDominatedPointsInOrderOfTime) {
  const std::vector<ChartPoint> points = {
      {"a", 10, 0, 0.1},   // on the front
      {"b", 20, 0, 0.01},  // on the front
      {"c", 15, 0, 0.2},   // slower and worse than a
      {"d", 30, 0, 0.01},  // as accurate as b, and slower
      {"e", 5, 0, 0.5},    // fastest
      {"f", 40, 0, 0},     // the reference: most accurate
  };
  EXPECT_THAT(pareto_front(points), ElementsAre(4, 0, 1, 5));
}

TEST(ParetoFrontTest, KeepsExactTiesAndDropsPartialOnes) {
  const std::vector<ChartPoint> points = {
      {"a", 10, 0, 0.1},          {"a again", 10, 0, 0.1},  // the same time and error: both stay
      {"same time", 10, 0, 0.2},                            // as fast, less accurate: out
      {"same error", 12, 0, 0.1},                           // as accurate, slower: out
      {"b", 20, 0, 0.01},
  };
  EXPECT_THAT(pareto_front(points), ElementsAre(0, 1, 4));
}

TEST(ParetoFrontTest, SingleAndNoPoints) {
  EXPECT_THAT(pareto_front({{"only", 3, 1, 0.5}}), ElementsAre(0));
  EXPECT_THAT(pareto_front({}), IsEmpty());
}

TEST(ParetoFrontTest, NonFinitePointsAreNeitherOnItNorDominate) {
  const std::vector<ChartPoint> points = {
      {"nan time", kNaN, 0, 0},  // would dominate everything if NaN compared as small
      {"a", 10, 0, 0.1},        {"inf error", 1, 0, kInf}, {"b", 20, 0, 0.05}, {"-inf time", -kInf, 0, 0},
  };
  EXPECT_THAT(pareto_front(points), ElementsAre(1, 3));
}

// ---- the chart ----

TEST(ParetoChartTest, IsWellFormedSvgWithAMarkerPerPointAndALegendEntryPerLane) {
  ChartOptions options;
  options.title = "Depth of field: kernel size";
  const std::string svg = pareto_chart_svg(three_lanes(), options);
  const Xml xml = parse_xml(svg);
  ASSERT_EQ(xml.error, "") << svg;
  ASSERT_FALSE(xml.elements.empty());
  EXPECT_EQ(xml.elements[0].name, "svg");
  EXPECT_EQ(xml.elements[0].attributes.at("xmlns"), "http://www.w3.org/2000/svg");
  EXPECT_EQ(xml.elements[0].attributes.at("version"), "1.1");
  EXPECT_EQ(xml.elements[0].attributes.at("font-family"), "sans-serif");
  EXPECT_THAT(svg, Not(HasSubstr("<script")));
  EXPECT_THAT(svg, Not(HasSubstr("href")));               // nothing external
  EXPECT_EQ(with_class(xml, "marker").size(), 15u + 3u);  // 15 points and 3 legend entries
  EXPECT_EQ(with_class(xml, "label").size(), 15u);
  EXPECT_EQ(with_class(xml, "front").size(), 3u);
  EXPECT_EQ(with_class(xml, "note").size(), 0u);
  // Each lane its own colour and shape.
  const Element* gl = marker_of(xml, "gl, 16 samples");
  const Element* vk = marker_of(xml, "vk, 16 samples");
  const Element* hlsl = marker_of(xml, "vk-hlsl, 16 samples");
  ASSERT_TRUE(gl && vk && hlsl);
  EXPECT_NE(gl->attributes.at("fill"), vk->attributes.at("fill"));
  EXPECT_NE(vk->attributes.at("fill"), hlsl->attributes.at("fill"));
  EXPECT_NE(gl->name, vk->name);  // circle and rect
  std::vector<std::string> legend_texts;
  for (const Element& e : xml.elements)
    if (e.name == "text" && e.parent != SIZE_MAX && xml.elements[e.parent].attributes.count("class") &&
        xml.elements[e.parent].attributes.at("class") == "legend")
      legend_texts.push_back(e.text);
  EXPECT_THAT(legend_texts, ElementsAre("gl", "vk", "vk-hlsl", "Pareto front", "time spread"));
}

TEST(ParetoChartTest, EscapesLabelsNamesAndTitle) {
  ChartOptions options;
  options.title = "fp32 & fp16";
  options.y_label = "RMSE <linear>";
  const std::vector<ChartSeries> series = {
      {"a<b", {{"<script>alert(\"x\")</script> 'q'", 10, 1, 0.1}, {"bad \xff byte\x01", 20, 1, 0.01}}}};
  const std::string svg = pareto_chart_svg(series, options);
  const Xml xml = parse_xml(svg);
  ASSERT_EQ(xml.error, "") << svg;
  EXPECT_THAT(svg, Not(HasSubstr("<script>")));
  EXPECT_THAT(svg, HasSubstr("&lt;script&gt;alert(&quot;x&quot;)&lt;/script&gt; &#39;q&#39;"));
  EXPECT_THAT(svg, HasSubstr("fp32 &amp; fp16"));
  EXPECT_THAT(svg, HasSubstr("RMSE &lt;linear&gt;"));
  EXPECT_THAT(svg, HasSubstr("bad \xEF\xBF\xBD byte\xEF\xBF\xBD"));  // U+FFFD for the bad byte and the control
  const auto labels = with_class(xml, "label");
  ASSERT_EQ(labels.size(), 2u);
  EXPECT_EQ(labels[0]->text, "<script>alert(\"x\")</script> 'q'");
  ASSERT_NE(marker_of(xml, "a<b, <script>alert(\"x\")</script> 'q'"), nullptr);
}

TEST(ParetoChartTest, MarkersLandOnTheLogScale) {
  const std::vector<ChartSeries> series = {
      {"gl", {{"p10", 10, 0, 0.01}, {"p20", 20, 0, 0.001}, {"p100", 100, 0, 0.1}, {"p35", 35, 0, 0.02}}}};
  const Xml xml = parse_xml(pareto_chart_svg(series, ChartOptions{}));
  ASSERT_EQ(xml.error, "");
  // Ticks at 1, 2, 5 x 10^k across 10..100 ms and 0.001..0.1.
  for (const char* t : {"10", "20", "50", "100"}) EXPECT_NE(tick(xml, "x-tick", t), nullptr) << t;
  for (const char* t : {"0.001", "0.002", "0.005", "0.01", "0.02", "0.05", "0.1"})
    EXPECT_NE(tick(xml, "y-tick", t), nullptr) << t;
  const double x10 = tick(xml, "x-tick", "10")->number("x");
  const double x100 = tick(xml, "x-tick", "100")->number("x");
  ASSERT_GT(x100 - x10, 100);
  const Element* p10 = marker_of(xml, "gl, p10");
  const Element* p20 = marker_of(xml, "gl, p20");
  const Element* p35 = marker_of(xml, "gl, p35");
  const Element* p100 = marker_of(xml, "gl, p100");
  ASSERT_TRUE(p10 && p20 && p35 && p100);
  EXPECT_NEAR(p10->number("cx"), x10, 0.02);
  EXPECT_NEAR(p100->number("cx"), x100, 0.02);
  EXPECT_NEAR(p20->number("cx"), x10 + (x100 - x10) * std::log10(2.0), 0.02);
  EXPECT_NEAR(p35->number("cx"), x10 + (x100 - x10) * std::log10(3.5), 0.02);
  // No point on the frame: the axis is padded.
  const Element* frame = nullptr;
  for (const Element& e : xml.elements)
    if (e.name == "rect" && e.attributes.at("fill") == "none") frame = &e;
  ASSERT_NE(frame, nullptr);
  EXPECT_GT(p10->number("cx"), frame->number("x") + 10);
  EXPECT_LT(p100->number("cx"), frame->number("x") + frame->number("width") - 10);
  // y: tick labels sit 4 px below their value's line (baseline of 11 px text).
  const double y001 = tick(xml, "y-tick", "0.001")->number("y") - 4;
  const double y01 = tick(xml, "y-tick", "0.1")->number("y") - 4;
  EXPECT_NEAR(p20->number("cy"), y001, 0.02);
  EXPECT_NEAR(p100->number("cy"), y01, 0.02);
  EXPECT_NEAR(p10->number("cy"), y001 + (y01 - y001) / 2, 0.02);
  EXPECT_NEAR(p35->number("cy"), y001 + (y01 - y001) * std::log10(20.0) / 2, 0.02);
}

TEST(ParetoChartTest, LinearAxesPlaceValuesProportionally) {
  ChartOptions options;
  options.log_x = false;
  options.log_y = false;
  const std::vector<ChartSeries> series = {{"gl", {{"a", 0, 0, 0}, {"b", 5, 0, 0.5}, {"c", 10, 0, 1}}}};
  const Xml xml = parse_xml(pareto_chart_svg(series, options));
  ASSERT_EQ(xml.error, "");
  const Element* a = marker_of(xml, "gl, a");
  const Element* b = marker_of(xml, "gl, b");
  const Element* c = marker_of(xml, "gl, c");
  ASSERT_TRUE(a && b && c);
  EXPECT_NEAR(b->number("cx"), (a->number("cx") + c->number("cx")) / 2, 0.02);
  EXPECT_NEAR(b->number("cy"), (a->number("cy") + c->number("cy")) / 2, 0.02);
  ASSERT_NE(tick(xml, "x-tick", "0"), nullptr);
  EXPECT_NEAR(a->number("cx"), tick(xml, "x-tick", "0")->number("x"), 0.02);
  ASSERT_TRUE(tick(xml, "y-tick", "0") && tick(xml, "y-tick", "1"));
  EXPECT_NEAR(a->number("cy"), tick(xml, "y-tick", "0")->number("y") - 4, 0.02);
  EXPECT_NEAR(c->number("cy"), tick(xml, "y-tick", "1")->number("y") - 4, 0.02);
  // A zero error is an ordinary value on a linear axis: no separate row.
  EXPECT_EQ(tick(xml, "y-tick", "0 (reference)"), nullptr);
}

TEST(ParetoChartTest, ZeroErrorGoesOnItsOwnRowBelowTheLogScale) {
  const std::vector<ChartSeries> series = {{"gl", {{"fast", 5, 0, 0.1}, {"exact", 50, 2, 0}, {"mid", 12, 0, 1e-4}}}};
  const Xml xml = parse_xml(pareto_chart_svg(series, ChartOptions{}));
  ASSERT_EQ(xml.error, "");
  const Element* row = tick(xml, "y-tick", "0 (reference)");
  ASSERT_NE(row, nullptr);
  const Element* exact = marker_of(xml, "gl, exact");
  ASSERT_NE(exact, nullptr);
  EXPECT_NEAR(exact->number("cy"), row->number("y") - 4, 0.02);
  for (const Element* t : with_class(xml, "y-tick")) {
    if (t == row) continue;
    EXPECT_LT(t->number("y"), row->number("y") - 20) << t->text;  // well below the lowest decade
  }
  // The reference is on the front: the staircase ends on it.
  const auto fronts = with_class(xml, "front");
  ASSERT_EQ(fronts.size(), 1u);
  const auto vertices = polyline(*fronts[0]);
  ASSERT_FALSE(vertices.empty());
  EXPECT_NEAR(vertices.back().first, exact->number("cx"), 0.02);
  EXPECT_NEAR(vertices.back().second, exact->number("cy"), 0.02);
}

TEST(ParetoChartTest, FrontIsAStaircaseThroughTheFrontPointsOnly) {
  const std::vector<ChartSeries> series = {
      {"vk", {{"a", 10, 0, 0.1}, {"c", 15, 0, 0.2}, {"b", 20, 0, 0.01}, {"d", 30, 0, 0.01}}}};
  const Xml xml = parse_xml(pareto_chart_svg(series, ChartOptions{}));
  ASSERT_EQ(xml.error, "");
  const Element* a = marker_of(xml, "vk, a");
  const Element* b = marker_of(xml, "vk, b");
  ASSERT_TRUE(a && b);
  const auto fronts = with_class(xml, "front");
  ASSERT_EQ(fronts.size(), 1u);
  const auto v = polyline(*fronts[0]);
  ASSERT_EQ(v.size(), 3u);  // a, the corner at b's time and a's error, b
  EXPECT_NEAR(v[0].first, a->number("cx"), 0.02);
  EXPECT_NEAR(v[0].second, a->number("cy"), 0.02);
  EXPECT_NEAR(v[1].first, b->number("cx"), 0.02);
  EXPECT_NEAR(v[1].second, a->number("cy"), 0.02);
  EXPECT_NEAR(v[2].first, b->number("cx"), 0.02);
  EXPECT_NEAR(v[2].second, b->number("cy"), 0.02);
}

TEST(ParetoChartTest, SpreadIsAHorizontalBarThroughTheMarker) {
  ChartOptions options;
  options.log_x = false;
  const std::vector<ChartSeries> series = {{"gl", {{"a", 10, 2, 0.1}, {"b", 20, 0, 0.01}}}};
  const Xml xml = parse_xml(pareto_chart_svg(series, options));
  ASSERT_EQ(xml.error, "");
  const Element* a = marker_of(xml, "gl, a");
  const Element* b = marker_of(xml, "gl, b");
  ASSERT_TRUE(a && b);
  const double px_per_ms = (b->number("cx") - a->number("cx")) / 10;
  // The bar is the first path of the point's group: "M left,y H right M ...".
  const Element* bar = nullptr;
  for (const Element& e : xml.elements)
    if (e.name == "path" && e.parent == a->parent) bar = &e;
  ASSERT_NE(bar, nullptr);
  double left = 0, y = 0, right = 0;
  ASSERT_EQ(std::sscanf(bar->attributes.at("d").c_str(), "M%lf,%lf H%lf", &left, &y, &right), 3);
  EXPECT_NEAR(left, a->number("cx") - 2 * px_per_ms, 0.05);
  EXPECT_NEAR(right, a->number("cx") + 2 * px_per_ms, 0.05);
  EXPECT_NEAR(y, a->number("cy"), 0.02);
  for (const Element& e : xml.elements) EXPECT_FALSE(e.name == "path" && e.parent == b->parent) << "b has no spread";
}

TEST(ParetoChartTest, NonFinitePointsAreLeftOutAndNoted) {
  const std::vector<ChartSeries> series = {{"gl",
                                            {{"good", 10, 1, 0.01},
                                             {"nan time", kNaN, 1, 0.01},
                                             {"inf error", 12, 1, kInf},
                                             {"both", -kInf, 1, kNaN},
                                             {"zero time", 0, 0, 0.1},
                                             {"negative error", 15, 0, -0.5},
                                             {"nan spread", 20, kNaN, 0.001}}}};
  const std::string svg = pareto_chart_svg(series, ChartOptions{});
  const Xml xml = parse_xml(svg);
  ASSERT_EQ(xml.error, "") << svg;
  EXPECT_NE(marker_of(xml, "gl, good"), nullptr);
  EXPECT_NE(marker_of(xml, "gl, nan spread"), nullptr);
  for (const char* left_out : {"gl, nan time", "gl, inf error", "gl, both", "gl, zero time", "gl, negative error"})
    EXPECT_EQ(marker_of(xml, left_out), nullptr) << left_out;
  std::vector<std::string> notes;
  for (const Element* e : with_class(xml, "note")) notes.push_back(e->text);
  EXPECT_THAT(notes, ElementsAre("Not drawn: gl, nan time: time nan ms", "Not drawn: gl, inf error: error inf",
                                 "Not drawn: gl, both: time -inf ms; error nan",
                                 "Not drawn: gl, zero time: time 0 ms, not on a log axis",
                                 "Not drawn: gl, negative error: error -0.5, not on a log axis",
                                 "No spread bar: gl, nan spread: spread nan ms"));
  // No number in any attribute is anything but finite.
  for (const Element& e : xml.elements)
    for (const auto& [name, value] : e.attributes) {
      EXPECT_THAT(value, Not(HasSubstr("nan"))) << e.name << " " << name;
      EXPECT_THAT(value, Not(HasSubstr("inf"))) << e.name << " " << name;
    }
  // The notes sit below the chart, which grows to hold them.
  const Element& root = xml.elements[0];
  EXPECT_GT(root.number("height"), 480);
  for (const Element* e : with_class(xml, "note")) {
    EXPECT_GT(e->number("y"), 480);
    EXPECT_LT(e->number("y"), root.number("height"));
  }
}

TEST(ParetoChartTest, NothingDrawableStillGivesAValidChart) {
  const std::vector<ChartSeries> series = {{"gl", {}}, {"vk", {{"x", kNaN, 0, kNaN}}}};
  const std::string svg = pareto_chart_svg(series, ChartOptions{});
  const Xml xml = parse_xml(svg);
  ASSERT_EQ(xml.error, "") << svg;
  EXPECT_EQ(with_class(xml, "note").size(), 1u);
  EXPECT_GE(with_class(xml, "x-tick").size(), 2u);
  EXPECT_GE(with_class(xml, "y-tick").size(), 2u);
}

TEST(ParetoChartTest, LabelsOfClosePointsDoNotOverlap) {
  // Two lanes with nearly the same time and error: their labels must go to different places.
  const std::vector<ChartSeries> series = {{"gl", {{"43 samples", 15, 0, 0.003}, {"16 samples", 5, 0, 0.1}}},
                                           {"vk", {{"43 samples", 15.3, 0, 0.0031}, {"16 samples", 5.1, 0, 0.1}}}};
  const Xml xml = parse_xml(pareto_chart_svg(series, ChartOptions{}));
  ASSERT_EQ(xml.error, "");
  const auto labels = with_class(xml, "label");
  ASSERT_EQ(labels.size(), 4u);
  // Label boxes as the text extends from its anchor; 11 px text, about 0.58 em per character.
  const auto box = [](const Element* e) {
    const double w = static_cast<double>(e->text.size()) * 11 * 0.58;
    const std::string& anchor = e->attributes.at("text-anchor");
    const double x = e->number("x"), y = e->number("y");
    const double left = anchor == "start" ? x : anchor == "end" ? x - w : x - w / 2;
    return std::array<double, 4>{left, y - 9, left + w, y + 3};
  };
  for (size_t i = 0; i < labels.size(); ++i)
    for (size_t j = i + 1; j < labels.size(); ++j) {
      const auto a = box(labels[i]), b = box(labels[j]);
      const bool apart = a[2] <= b[0] || b[2] <= a[0] || a[3] <= b[1] || b[3] <= a[1];
      EXPECT_TRUE(apart) << labels[i]->text << " and " << labels[j]->text;
    }
}

TEST(ParetoChartTest, IsDeterministic) {
  ChartOptions options;
  options.title = "fp32 vs fp16";
  const std::string first = pareto_chart_svg(three_lanes(), options);
  std::vector<ChartSeries> other = three_lanes();
  other[1].points[2].error = 0.5;
  const std::string changed = pareto_chart_svg(other, options);
  const std::string again = pareto_chart_svg(three_lanes(), options);
  EXPECT_EQ(first, again);
  EXPECT_NE(first, changed);
}

TEST(ParetoChartTest, ManyDecadesGetDecadeTicksOnly) {
  const std::vector<ChartSeries> series = {{"gl", {{"a", 1, 0, 1e-9}, {"b", 2, 0, 1e-1}}}};
  const Xml xml = parse_xml(pareto_chart_svg(series, ChartOptions{}));
  ASSERT_EQ(xml.error, "");
  std::vector<std::string> ticks;
  for (const Element* e : with_class(xml, "y-tick")) ticks.push_back(e->text);
  EXPECT_THAT(ticks, ElementsAre("1e-9", "1e-8", "1e-7", "1e-6", "1e-5", "1e-4", "0.001", "0.01", "0.1"));
}

}  // namespace
}  // namespace xshade::accuracy
