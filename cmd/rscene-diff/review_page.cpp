// review.md and index.html of rscene-diff --review (review.hpp).
#include <algorithm>
#include <map>

#include "rscene-diff/review.hpp"

namespace rscene::diffout {
namespace {

// The folder a record sits in: its path less the last part (a child
// record's `/World/Cart[1]` sits in /World), "(scene)" for records without
// a path (environment, solver, materials by name ...).
std::string folderOf(const RecordDiff& r) {
  if (r.path.empty() || r.path[0] != '/') return "(scene)";
  std::string p = r.path;
  if (std::size_t b = p.find('['); b != std::string::npos) p.resize(b);
  std::size_t slash = p.rfind('/');
  return slash == 0 ? "/" : p.substr(0, slash);
}

// The record as a row names it: its kind and path, or (no path) its kind
// and key.
std::string recordName(const RecordDiff& r) {
  std::string s = r.tag;
  if (!r.path.empty()) s += " " + r.path;
  else if (!r.key.empty() && r.key != r.tag) s += " " + r.key;
  if (r.renamed()) s += " (was " + r.oldPath + ")";
  return s;
}

const char* sign(Change c) { return c == Change::Added ? "added" : c == Change::Removed ? "removed" : "changed"; }

// A value in a GitHub table cell: Markdown's specials and `|` escaped,
// HTML's `&` and `<` as entities, one line.
std::string md(std::string_view v) {
  std::string s;
  for (char c : v) {
    switch (c) {
      case '|': s += "\\|"; break;
      case '\\': case '`': case '*': case '_': case '[': case ']': case '#': case '~': case '!': case '$':
        s += '\\';
        s += c;
        break;
      case '&': s += "&amp;"; break;
      case '<': s += "&lt;"; break;
      case '>': s += "&gt;"; break;
      case '\n': case '\r': s += ' '; break;
      default: s += c;
    }
  }
  return s;
}

// The longest run of backticks in `v`.
std::size_t longestTicks(std::string_view v) {
  std::size_t best = 0, run = 0;
  for (char c : v) {
    run = c == '`' ? run + 1 : 0;
    best = std::max(best, run);
  }
  return best;
}

// `v` as a Markdown code span: backslashes are literal there, so nothing is
// escaped; the span's backtick string is longer than any run inside, and
// padded with a space where `v` starts or ends with a backtick.
std::string codeSpan(std::string_view v) {
  std::string ticks(longestTicks(v) + 1, '`');
  std::string body;
  for (char c : v) body += c == '\n' || c == '\r' ? ' ' : c;
  bool pad = !body.empty() && (body.front() == '`' || body.back() == '`');
  return ticks + (pad ? " " : "") + body + (pad ? " " : "") + ticks;
}

std::string html(std::string_view v) {
  std::string s;
  for (char c : v) {
    switch (c) {
      case '&': s += "&amp;"; break;
      case '<': s += "&lt;"; break;
      case '>': s += "&gt;"; break;
      case '"': s += "&quot;"; break;
      case '\'': s += "&#39;"; break;
      default: s += c;
    }
  }
  return s;
}

std::string base64(std::string_view bytes) {
  static const char* t = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    unsigned n = (unsigned char)bytes[i] << 16 | (unsigned char)bytes[i + 1] << 8 | (unsigned char)bytes[i + 2];
    out += t[n >> 18], out += t[(n >> 12) & 63], out += t[(n >> 6) & 63], out += t[n & 63];
  }
  if (i < bytes.size()) {
    unsigned n = (unsigned char)bytes[i] << 16 | (i + 1 < bytes.size() ? (unsigned char)bytes[i + 1] << 8 : 0);
    out += t[n >> 18], out += t[(n >> 12) & 63];
    out += i + 1 < bytes.size() ? t[(n >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

// The old and new value of a field as a row shows them.
std::pair<std::string, std::string> values(const FieldDiff& f) {
  auto withDefault = [](const std::string& v, bool d) { return d ? v + " (default)" : v; };
  if (f.summarized) {
    std::string counts = std::to_string(f.oldCount) + " \u2192 " + std::to_string(f.newCount) + " entries";
    if (f.changedCount) counts += ", " + std::to_string(f.changedCount) + " changed";
    return {f.change == Change::Added ? "" : std::to_string(f.oldCount) + " entries",
            f.change == Change::Removed ? "" : counts};
  }
  return {f.change == Change::Added ? "" : withDefault(f.oldValue, f.oldDefault),
          f.change == Change::Removed ? "" : withDefault(f.newValue, f.newDefault)};
}

// An added or removed record in one row: its first fields as name=value.
std::string wholeRecord(const RecordDiff& r, std::size_t shown) {
  std::string s;
  std::size_t n = 0;
  for (const FieldDiff& f : r.fields) {
    if (f.entry) continue;
    if (n == shown) {
      s += ", ...";
      break;
    }
    auto [o, v] = values(f);
    s += (n ? ", " : "") + f.name + "=" + (r.change == Change::Added ? v : o);
    ++n;
  }
  return s;
}

std::map<std::string, std::vector<const RecordDiff*>> byFolder(const DiffResult& result) {
  std::map<std::string, std::vector<const RecordDiff*>> out;
  for (const RecordDiff& r : result.records) out[folderOf(r)].push_back(&r);
  return out;
}

std::string summary(const DiffResult& result) {
  if (result.same()) return "no change";
  std::string s;
  auto add = [&](std::size_t n, const char* what) {
    if (!n) return;
    if (!s.empty()) s += ", ";
    s += std::to_string(n) + " " + what;
  };
  add(result.count(Change::Changed), "changed");
  add(result.count(Change::Added), "added");
  add(result.count(Change::Removed), "removed");
  std::size_t n = result.records.size();
  return std::to_string(n) + (n == 1 ? " record: " : " records: ") + s;
}

}  // namespace

std::string reviewMarkdown(const std::string& oldName, const std::string& newName, const DiffResult& result,
                           bool images, const std::string& note, const std::string& lineDiff) {
  // A deleted scene is named by its old name.
  std::string out = "### Scene review: " + codeSpan(newName == "/dev/null" ? oldName : newName) + "\n\n";
  out += "**" + (lineDiff.empty() ? summary(result) : std::string("does not parse")) + "** (" + md(oldName) +
         " &rarr; " + md(newName) + ")";
  if (!note.empty()) out += ". " + md(note);
  out += "\n\n";
  if (images) {
    out += "| before | after | changes |\n|---|---|---|\n";
    out += "| ![before](before.png) | ![after](after.png) | ![changes](changes.png) |\n\n";
  }
  for (const auto& [folder, records] : byFolder(result)) {
    out += "#### " + md(folder) + "\n\n| record | change | field | old | new |\n|---|---|---|---|---|\n";
    for (const RecordDiff* r : records) {
      std::string name = md(recordName(*r));
      if (r->fields.empty() || r->change != Change::Changed) {
        std::string whole = md(wholeRecord(*r, 4));
        out += "| " + name + " | " + sign(r->change) + " | | " + (r->change == Change::Removed ? whole : "") + " | " +
               (r->change == Change::Added ? whole : "") + " |\n";
        continue;
      }
      bool first = true;
      for (const FieldDiff& f : r->fields) {
        auto [o, n] = values(f);
        out += "| " + (first ? name : std::string()) + " | " + (first ? sign(r->change) : "") + " | " + md(f.name) +
               " | " + md(o) + " | " + md(n) + " |\n";
        first = false;
      }
    }
    out += "\n";
  }
  if (!lineDiff.empty()) {
    // A fence longer than any backtick run in the lines: a line of the
    // scene cannot close it and turn the rest into Markdown.
    std::string fence(std::max<std::size_t>(3, longestTicks(lineDiff) + 1), '`');
    out += fence + "diff\n" + lineDiff + (lineDiff.back() == '\n' ? "" : "\n") + fence + "\n";
  }
  return out;
}

std::string reviewHtml(const std::string& oldName, const std::string& newName, const DiffResult& result,
                       const std::string& beforePng, const std::string& afterPng, const std::string& changesPng,
                       const std::string& note, const std::string& lineDiff) {
  const bool images = !beforePng.empty();
  std::string out =
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; img-src data:; "
      "style-src 'unsafe-inline'; script-src 'unsafe-inline'\">\n"
      "<title>Scene review: " + html(newName == "/dev/null" ? oldName : newName) + "</title>\n<style>\n"
      "body{font-family:system-ui,sans-serif;margin:1.5em;color:#222}\n"
      "table{border-collapse:collapse;margin:.5em 0 1.5em}\n"
      "td,th{border:1px solid #ccc;padding:.2em .5em;text-align:left;font-family:ui-monospace,monospace;"
      "font-size:90%;vertical-align:top}\n"
      "th{background:#f0f0f0}\n.added{color:#15803d}.removed{color:#b91c1c}.changed{color:#b45309}\n"
      "#stage{position:relative;display:inline-block;line-height:0}\n"
      "#stage img{max-width:100%}\n"
      "#overlay{position:absolute;top:0;left:0;height:100%;overflow:hidden;border-right:2px solid #fff}\n"
      "#overlay img{max-width:none}\n"
      "button{font-size:100%;margin-right:.3em}button[aria-pressed=true]{font-weight:bold}\n"
      "pre{background:#f6f6f6;padding:.5em;overflow:auto}\n"
      "</style>\n</head>\n<body>\n";
  out += "<h1>Scene review: " + html(newName == "/dev/null" ? oldName : newName) + "</h1>\n";
  out += "<p><b>" + html(lineDiff.empty() ? summary(result) : std::string("does not parse")) + "</b> (" + html(oldName) + " &rarr; " + html(newName) + ")";
  if (!note.empty()) out += ". " + html(note);
  out += "</p>\n";
  if (images) {
    const std::string b = "data:image/png;base64," + base64(beforePng);
    const std::string a = "data:image/png;base64," + base64(afterPng);
    const std::string c = "data:image/png;base64," + base64(changesPng);
    out += "<p id=\"controls\"><button id=\"show-before\" aria-pressed=\"false\">before</button>"
           "<button id=\"show-after\" aria-pressed=\"true\">after</button>"
           "<button id=\"show-changes\" aria-pressed=\"false\">changes</button>"
           "<button id=\"show-slider\" aria-pressed=\"false\">slider</button> "
           "<label id=\"slider-label\" hidden>before &larr; <input id=\"slider\" type=\"range\" min=\"0\" "
           "max=\"100\" value=\"50\"> &rarr; after</label></p>\n";
    out += "<div id=\"stage\"><img id=\"view\" alt=\"after\" src=\"" + a + "\">"
           "<div id=\"overlay\" hidden><img id=\"overlay-img\" alt=\"before\" src=\"" + b + "\"></div></div>\n";
    out += "<p><small>Keys: b before, a after, c changes, s slider.</small></p>\n";
    out += "<script>\n\"use strict\";\nconst srcs={before:\"" + b + "\",after:\"" + a + "\",changes:\"" + c +
           "\"};\n";
    out += R"JS(const view=document.getElementById("view"),overlay=document.getElementById("overlay"),
  overlayImg=document.getElementById("overlay-img"),slider=document.getElementById("slider"),
  label=document.getElementById("slider-label");
function press(which){for(const k of ["before","after","changes","slider"])
  document.getElementById("show-"+k).setAttribute("aria-pressed",String(k===which));}
function show(which){
  if(which==="slider"){view.src=srcs.after;view.alt="after";overlay.hidden=false;label.hidden=false;clip();}
  else{overlay.hidden=true;label.hidden=true;view.src=srcs[which];view.alt=which;}
  press(which);document.body.dataset.showing=which;}
function clip(){overlay.style.width=slider.value+"%";overlayImg.style.width=view.clientWidth+"px";}
for(const k of ["before","after","changes","slider"])
  document.getElementById("show-"+k).addEventListener("click",()=>show(k));
slider.addEventListener("input",clip);
view.addEventListener("load",()=>{if(!overlay.hidden)clip();});
window.addEventListener("resize",clip);
document.addEventListener("keydown",e=>{const m={b:"before",a:"after",c:"changes",s:"slider"}[e.key];if(m)show(m);});
// A self-check a headless browser reads back (--dump-dom): the images
// decode, and each button shows its image.
window.addEventListener("load",()=>{
  const out=[];const imgs=[...document.images];
  const fetched=performance.getEntriesByType("resource").filter(e=>!e.name.startsWith("data:"));
  out.push("requests "+fetched.length);
  out.push("images "+imgs.length+" decoded "+imgs.filter(i=>i.complete&&i.naturalWidth>0).length);
  for(const k of ["before","changes","after"]){show(k);out.push(k+" "+(view.src===srcs[k]));}
  show("slider");out.push("slider "+(!overlay.hidden&&overlayImg.src===srcs.before&&view.src===srcs.after));
  show(initial);
  document.body.dataset.selfcheck=out.join("; ");});
const initial={"#before":"before","#changes":"changes","#slider":"slider"}[location.hash]||"after";
show(initial);
</script>
)JS";
  }
  if (!lineDiff.empty()) out += "<pre>" + html(lineDiff) + "</pre>\n";
  for (const auto& [folder, records] : byFolder(result)) {
    out += "<h2>" + html(folder) + "</h2>\n<table>\n<tr><th>record</th><th>change</th><th>field</th><th>old</th>"
           "<th>new</th></tr>\n";
    for (const RecordDiff* r : records) {
      std::size_t rows = r->fields.size();
      std::string head = "<td rowspan=\"" + std::to_string(rows) + "\">" + html(r->tag + " " + recordName(*r)) +
                         "</td><td rowspan=\"" + std::to_string(rows) + "\" class=\"" + sign(r->change) + "\">" +
                         sign(r->change) + "</td>";
      if (r->fields.empty() || r->change != Change::Changed) {
        std::string whole = "<details><summary>" + html(wholeRecord(*r, 4)) + "</summary>" +
                            html(wholeRecord(*r, r->fields.size())) + "</details>";
        head = "<td>" + html(r->tag + " " + recordName(*r)) + "</td><td class=\"" + sign(r->change) + "\">" +
               sign(r->change) + "</td>";
        out += "<tr>" + head + "<td></td><td>" + (r->change == Change::Removed ? whole : "") + "</td><td>" +
               (r->change == Change::Added ? whole : "") + "</td></tr>\n";
        continue;
      }
      bool first = true;
      for (const FieldDiff& f : r->fields) {
        auto [o, n] = values(f);
        out += "<tr>" + (first ? head : std::string()) + "<td>" + html(f.name) + "</td><td>" + html(o) +
               "</td><td>" + html(n) + "</td></tr>\n";
        first = false;
      }
    }
    out += "</table>\n";
  }
  out += "</body>\n</html>\n";
  return out;
}

}  // namespace rscene::diffout
