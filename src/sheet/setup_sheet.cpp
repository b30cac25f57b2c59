// The setup sheet (setup_sheet.hpp) as one HTML file that needs nothing else: its style inline, its pictures inline
// as base64 PNG data, so that it can be mailed, opened offline and printed as it is. Printed, each setup starts a
// page of its own (the machinist takes one page to the machine per clamping). Every text that comes from the job
// (names, descriptions, paths, reasons) is escaped: a job file is input, and must not become markup.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "rosmill/error.hpp"
#include "rosmill/gcode/work_offset.hpp"
#include "rosmill/geometry/placement.hpp"
#include "rosmill/job/job_spec.hpp"
#include "rosmill/sheet/setup_sheet.hpp"

namespace rosmill::core::sheet {
namespace {

constexpr int kPictureWidth = 900, kPictureHeight = 600;  // 3:2, 180 mm x 120 mm on an A4 page

// Printable: A4 with the margins of most office printers, the colour swatches printed (browsers leave backgrounds
// out by default; the swatch is a border, which they print, and print-color-adjust asks for exact colours anyway).
const char* const kStyle = R"(
@page { size: A4; margin: 12mm; }
* { -webkit-print-color-adjust: exact; print-color-adjust: exact; }
body { font-family: "DejaVu Sans", Arial, Helvetica, sans-serif; font-size: 10pt; color: #000; max-width: 186mm;
       margin: 0 auto; }
h1 { font-size: 16pt; margin: 0 0 3mm; }
h2 { font-size: 13pt; margin: 0 0 2mm; padding-bottom: 1mm; border-bottom: 0.4mm solid #000; }
h3 { font-size: 11pt; margin: 3mm 0 1mm; }
table { border-collapse: collapse; width: 100%; margin: 1mm 0 3mm; }
th, td { border: 0.2mm solid #999; padding: 0.8mm 1.5mm; text-align: left; vertical-align: top; }
table.facts th { width: 26%; background: #eee; }
table.operations th { background: #eee; }
td.n, th.n { text-align: right; white-space: nowrap; }
tfoot td { font-weight: bold; }
ul.boxes { margin: 0.5mm 0 0; padding-left: 5mm; }
.swatch { display: inline-block; width: 0; height: 0.9em; border-left: 1.6em solid; vertical-align: middle; }
.note { font-style: italic; }
figure { margin: 0; }
figure img { display: block; width: 100%; max-width: 180mm; height: auto; margin: 0 auto;
             border: 0.2mm solid #999; }
figcaption { font-size: 8.5pt; text-align: center; margin-top: 1mm; }
section.setup { break-before: page; page-break-before: always; }
table, figure, tr { break-inside: avoid; page-break-inside: avoid; }
@media screen {
  body { margin: 8mm auto; }
  section.setup { margin-top: 12mm; }
}
)";

std::string escape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string base64(const std::vector<unsigned char>& bytes) {
  static const char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const size_t n = std::min<size_t>(3, bytes.size() - i);
    uint32_t v = uint32_t(bytes[i]) << 16;
    if (n > 1) v |= uint32_t(bytes[i + 1]) << 8;
    if (n > 2) v |= bytes[i + 2];
    out += kDigits[v >> 18 & 63];
    out += kDigits[v >> 12 & 63];
    out += n > 1 ? kDigits[v >> 6 & 63] : '=';
    out += n > 2 ? kDigits[v & 63] : '=';
  }
  return out;
}

// A length or an area as a person reads it: at most `decimals` places, no trailing zeros, no "-0".
std::string number(double v, int decimals = 2) {
  if (!std::isfinite(v)) return "?";
  char s[64];
  std::snprintf(s, sizeof s, "%.*f", decimals, v);
  std::string text = s;
  if (text.find('.') != std::string::npos) {
    text.erase(text.find_last_not_of('0') + 1);
    if (text.back() == '.') text.pop_back();
  }
  return text == "-0" ? "0" : text;
}

std::string point(const Vec3& p) { return "(" + number(p.x()) + ", " + number(p.y()) + ", " + number(p.z()) + ")"; }

// Seconds as h:mm:ss (a job, a setup) or mm:ss (an operation; minutes past 59 keep counting).
std::string duration(double seconds, bool hours) {
  if (!std::isfinite(seconds) || seconds < 0) return "?";
  const long long total = std::llround(seconds);
  char s[64];
  if (hours)
    std::snprintf(s, sizeof s, "%lld:%02lld:%02lld", total / 3600, total / 60 % 60, total % 60);
  else
    std::snprintf(s, sizeof s, "%02lld:%02lld", total / 60, total % 60);
  return s;
}

std::string fact(const std::string& name, const std::string& html) {
  return "<tr><th>" + name + "</th><td>" + html + "</td></tr>\n";
}

// Every tool the job's programs load, by its number in the controller's tool table: what the operator puts in each
// pocket before the run.
void tools_table(std::ostream& out, const job::JobReport& report) {
  std::vector<const job::OperationReport*> tools;
  for (const job::OperationReport& op : report.operations) {
    bool seen = false;
    for (const job::OperationReport* t : tools) seen |= t->tool_used.id == op.tool_used.id;
    if (!seen) tools.push_back(&op);
  }
  std::sort(tools.begin(), tools.end(), [](const job::OperationReport* a, const job::OperationReport* b) {
    return a->tool_used.id < b->tool_used.id;
  });
  out << "<h3>Tools</h3>\n<table class=\"operations\">\n<thead><tr><th class=\"n\">T</th><th>Tool</th><th>Cutter</th>"
         "<th class=\"n\">&Oslash; mm</th><th class=\"n\">Corner mm</th><th class=\"n\">Stick-out mm</th></tr>"
         "</thead>\n<tbody>\n";
  for (const job::OperationReport* op : tools) {
    const Tool& t = op->tool_used;
    out << "<tr><td class=\"n\">T" << t.id << "</td><td>" << escape(t.name.empty() ? op->tool : t.name) << "</td><td>"
        << cutter_type_name(t.cutter.type) << "</td><td class=\"n\">" << number(t.cutter.diameter)
        << "</td><td class=\"n\">" << number(t.cutter.corner_radius) << "</td><td class=\"n\">"
        << number(t.stick_out_mm()) << "</td></tr>\n";
  }
  out << "</tbody>\n</table>\n";
}

// The whole surface after the job: how many faces are within their limit, and each one left above it (where, how
// much, why), so that the operator knows before the next tool meets it.
void surface_html(std::ostream& out, const job::JobReport& report) {
  const job::SurfaceAccount& a = report.surface;
  if (!a.done) return;
  out << "<h3>Material left on the part</h3>\n<p>" << a.asked_faces << " faces to finish; "
      << (a.unfinished_faces ? std::to_string(a.unfinished_faces) + " left above their limit over " +
                                   number(a.unfinished_area, 1) + " mm&sup2;" + (report.accept_unfinished
                                                                                      ? " (the job accepts it)"
                                                                                      : " (the job is refused)")
                             : std::string("every one within its limit"))
      << "; material left " << number(a.min_left_mm, 3) << " to " << number(a.max_left_mm, 3) << " mm.</p>\n";
  if (!a.unfinished_faces) return;
  out << "<table class=\"unreachable\">\n<thead><tr><th class=\"n\">Face</th><th>Setup</th><th>Why</th>"
         "<th class=\"n\">Above mm&sup2;</th><th class=\"n\">Limit mm</th><th class=\"n\">Most left mm</th>"
         "<th>Where (workpiece frame, mm)</th></tr></thead>\n<tbody>\n";
  for (const job::FaceLeft& f : a.faces) {
    if (f.verdict != job::FaceVerdict::Above) continue;
    const std::string setup = f.setup >= 0 ? std::to_string(f.setup + 1) + " " + escape(report.setups[f.setup].name)
                                           : "none";
    out << "<tr><td class=\"n\">" << f.face << "</td><td>" << setup << "</td><td>"
        << job::reason_name(f.main_reason()) << "</td><td class=\"n\">" << number(f.above_area, 1)
        << "</td><td class=\"n\">" << number(f.limit, 3) << "</td><td class=\"n\">" << number(f.max_left_mm, 3)
        << "</td><td>" << point(f.most_at) << "</td></tr>\n";
  }
  out << "</tbody>\n</table>\n";
}

void job_header(std::ostream& out, const SheetJob& job) {
  const job::JobReport& report = *job.report;
  out << "<header>\n<h1>Setup sheet</h1>\n<table class=\"facts\">\n"
      << fact("Job", escape(job.title)) << fact("Setups", std::to_string(report.setups.size()))
      << fact("Operations", std::to_string(report.operations.size()))
      << fact("Estimated time", duration(report.time_s, true));
  if (report.cancelled) out << fact("Cancelled", "the job was stopped: only the operations it finished are listed");
  out << "</table>\n";
  if (report.part_area > 0) {
    out << "<h3>Not machined by any setup</h3>\n<p>" << number(report.unreachable_area, 1) << " mm&sup2; of the part's "
        << number(report.part_area, 1) << " mm&sup2; (" << number(100 * report.unreachable_area / report.part_area, 1)
        << " %)" << (report.unreachable.empty() ? "." : ":") << "</p>\n";
    if (!report.unreachable.empty()) {
      out << "<table class=\"unreachable\">\n<thead><tr><th>Why</th><th class=\"n\">Area mm&sup2;</th>"
             "<th>Centroid (workpiece frame, mm)</th></tr></thead>\n<tbody>\n";
      for (const setups::Unreached& u : report.unreachable)
        out << "<tr><td>" << escape(u.reason) << "</td><td class=\"n\">" << number(u.area, 1) << "</td><td>"
            << point(u.centroid) << "</td></tr>\n";
      out << "</tbody>\n</table>\n";
    }
  }
  tools_table(out, report);
  surface_html(out, report);
  out << "</header>\n";
}

std::string fixture_html(const fixture::Fixture& f) {
  std::string html = f.description.empty() ? (f.empty() ? "none: the part stands on the table" : "boxes")
                                           : escape(f.description);
  if (f.empty()) return html;
  html += "\n<ul class=\"boxes\">\n";
  for (const fixture::FixtureBox& b : f.boxes) {
    const Vec3 size = b.box.size();
    html += "<li>" + escape(b.name) + ": " + number(size.x()) + " &times; " + number(size.y()) + " &times; " +
            number(size.z()) + " mm</li>\n";
  }
  return html + "</ul>";
}

std::string work_offset_html(const job::SetupReport& s) {
  if (!s.work_offset) return "G54 as set on the controller";
  const gcode::WorkOffset& w = *s.work_offset;
  std::string html = escape(w.code()) + " at machine X" + number(w.origin.x(), 3) + " Y" + number(w.origin.y(), 3) +
                     " Z" + number(w.origin.z(), 3);
  if (std::abs(w.rotation_deg) > 1e-9) html += ", turned " + number(w.rotation_deg, 3) + "&deg; about Z";
  // The program writes the offset into the controller's table itself: the machinist need not enter it.
  if (!s.program.empty()) html += "; the program sets it (G10 L2 P" + std::to_string(w.index) + ")";
  return html;
}

std::string program_html(const std::string& program) {
  if (program.empty()) return "not written";
  const std::string name = std::filesystem::path(program).filename().string();
  return escape(name.empty() ? program : name);
}

std::string tool_cell(const job::OperationReport& op) {
  const Tool& t = op.tool_used;
  return "T" + std::to_string(t.id) + " " + escape(t.name.empty() ? op.tool : t.name);
}

void operations_table(std::ostream& out, const SheetJob& job, const job::SetupReport& s) {
  const job::JobReport& report = *job.report;
  out << "<table class=\"operations\">\n<thead><tr><th></th><th class=\"n\">#</th><th>Operation</th>"
         "<th>Strategy</th><th>Tool</th><th class=\"n\">&Oslash; mm</th><th class=\"n\">Flutes mm</th>"
         "<th class=\"n\">Stick-out mm</th><th class=\"n\">Holder &Oslash; mm</th><th class=\"n\">Time</th></tr>"
         "</thead>\n<tbody>\n";
  for (size_t k = 0; k < s.operations.size(); ++k) {
    const job::OperationReport& op = report.operations[s.operations[k]];
    const Tool& t = op.tool_used;
    out << "<tr><td><span class=\"swatch\" style=\"border-color:" << operation_colour(k) << "\"></span></td>"
        << "<td class=\"n\">" << s.operations[k] + 1 << "</td><td>" << escape(op.name)
        << (op.nothing_to_cut ? "<br><span class=\"note\">nothing left to cut</span>" : "") << "</td><td>"
        << escape(op.strategy) << "</td><td>" << tool_cell(op) << "</td><td class=\"n\">"
        << number(t.cutter.diameter) << "</td><td class=\"n\">" << number(t.cutter.flute_length)
        << "</td><td class=\"n\">" << number(t.stick_out_mm()) << "</td><td class=\"n\">" << number(t.holder_mm())
        << "</td><td class=\"n\">" << duration(op.time_s, false) << "</td></tr>\n";
  }
  out << "</tbody>\n<tfoot><tr><td colspan=\"9\">Setup total</td><td class=\"n\">" << duration(s.time_s, true)
      << "</td></tr></tfoot>\n</table>\n";
}

std::string picture_html(const SheetJob& job, const job::SetupReport& s, size_t number) {
  static const Mesh kNoPart;
  const Mesh part = placed(job.part ? *job.part : kNoPart, s.frame.placement);
  std::vector<const Job*> operations;
  for (size_t op : s.operations) operations.push_back(op < job.toolpaths.size() ? &job.toolpaths[op] : nullptr);
  const std::vector<unsigned char> png = setup_picture_png(part, s.fixture, operations, kPictureWidth, kPictureHeight);
  return "<figure><img src=\"data:image/png;base64," + base64(png) + "\" width=\"" + std::to_string(kPictureWidth) +
         "\" height=\"" + std::to_string(kPictureHeight) + "\" alt=\"setup " + std::to_string(number) +
         ": the part in its fixture with the toolpaths\">\n<figcaption>Seen from in front (&minus;Y), the right (+X) "
         "and above (+Z) of the setup; the fixture brown; each operation's cuts in its colour, rapids dashed."
         "</figcaption></figure>\n";
}

void setup_section(std::ostream& out, const SheetJob& job, size_t i) {
  const job::SetupReport& s = job.report->setups[i];
  const size_t count = job.report->setups.size();
  out << "<section class=\"setup\">\n<h2>Setup " << i + 1 << " of " << count << ": " << escape(s.name) << "</h2>\n"
      << "<table class=\"facts\">\n" << fact("Face down", escape(s.face_down))
      << fact("Tool axis (workpiece frame)", point(s.direction));
  if (!s.stock.empty()) {
    const Vec3 size = s.stock.size();
    out << fact("Stock at the start", number(size.x()) + " &times; " + number(size.y()) + " &times; " +
                                          number(size.z()) + " mm");
  }
  out << fact("Fixture", fixture_html(s.fixture))
      << fact("Datum", escape(job::datum_name(s.datum)) + std::string(" at ") + point(s.datum_point) +
                           " mm in the workpiece frame")
      << fact("Work offset", work_offset_html(s)) << fact("Program", program_html(s.program))
      << fact("Estimated time", duration(s.time_s, true)) << "</table>\n";
  operations_table(out, job, s);
  out << picture_html(job, s, i + 1) << "</section>\n";
}

// A report that names operations it does not hold is a bug upstream: say so rather than read past the end.
void check_report(const SheetJob& job) {
  if (!job.report) throw Error("setup sheet", "no job report");
  const job::JobReport& report = *job.report;
  for (size_t i = 0; i < report.setups.size(); ++i)
    for (size_t op : report.setups[i].operations)
      if (op >= report.operations.size())
        throw Error("setup sheet", "setup " + std::to_string(i + 1) + " lists operation " + std::to_string(op + 1) +
                                       " of " + std::to_string(report.operations.size()));
}

}  // namespace

std::string setup_sheet_html(const SheetJob& job) {
  check_report(job);
  std::ostringstream out;
  out << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>Setup sheet: "
      << escape(job.title) << "</title>\n<style>" << kStyle << "</style>\n</head>\n<body>\n";
  job_header(out, job);
  for (size_t i = 0; i < job.report->setups.size(); ++i) setup_section(out, job, i);
  out << "</body>\n</html>\n";
  return out.str();
}

void write_setup_sheet(const std::string& path, const SheetJob& job) {
  const std::string html = setup_sheet_html(job);  // before opening: a refused job leaves no empty file behind
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  if (!file) throw Error(path, "cannot open for writing");
  file.write(html.data(), static_cast<std::streamsize>(html.size()));
  file.close();
  if (!file) throw Error(path, "write failed");
}

}  // namespace rosmill::core::sheet
