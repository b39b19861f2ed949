//! The report's `index.html`, built from a [`Report`] by plain string formatting: every
//! text is escaped, every file it names is relative to the report folder.

use super::{Gallery, Report, Table, VERSION};

/// Escapes `&`, `<`, `>`, `"` and `'` for HTML text and attributes.
pub fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            c => out.push(c),
        }
    }
    out
}

/// A JavaScript string literal (JSON string rules; `<` escaped so `</script>` cannot
/// end the script).
pub fn js_string(text: &str) -> String {
    serde_json::to_string(text)
        .unwrap_or_else(|_| "\"\"".into())
        .replace('<', "\\u003c")
}

/// Reports on the console any file the page names but cannot load (registered first, in
/// the head, so it sees every load), so a headless check notices.
const WATCH: &str = "window.addEventListener('error', function (e) { var t = e.target; \
if (t && t !== window && (t.src || t.href)) { console.error('lightlab report: cannot load ' + (t.src || t.href)); } }, true);";

/// The whole page.
pub fn render_html(report: &Report) -> String {
    let mut body = String::new();
    body += &format!("<h1>{}</h1>\n", escape(&report.title));
    body += &provenance(report);
    for note in &report.notes {
        body += &format!("<p class=\"note\">{}</p>\n", escape(note));
    }
    if !report.links.is_empty() {
        body += "<ul class=\"links\">\n";
        for (label, href) in &report.links {
            body += &format!(
                "<li><a href=\"{}\">{}</a></li>\n",
                escape(href),
                escape(label)
            );
        }
        body += "</ul>\n";
    }
    if !report.viewer.is_empty() {
        body += &viewer(report);
    }
    for table in &report.tables {
        body += &table_html(table);
    }
    for gallery in &report.galleries {
        body += &gallery_html(gallery);
    }
    let scripts: String = report
        .viewer
        .iter()
        .map(|v| format!("<script src=\"img/{}.js\"></script>\n", escape(&v.key)))
        .collect();
    let list: Vec<String> = report
        .viewer
        .iter()
        .map(|v| {
            format!(
                "{{label: {}, key: {}}}",
                js_string(&v.label),
                js_string(&v.key)
            )
        })
        .collect();
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <title>{title}</title>\n<link rel=\"icon\" href=\"data:,\">\n\
         <link rel=\"stylesheet\" href=\"report.css\">\n<script>{WATCH}</script>\n</head>\n<body>\n{body}\
         {scripts}<script>window.LIGHTLAB_VIEWER = [{list}];</script>\n\
         <script src=\"report.js\"></script>\n</body>\n</html>\n",
        title = escape(&report.title),
        list = list.join(", ")
    )
}

fn provenance(report: &Report) -> String {
    let seeds: Vec<String> = report.seeds.iter().map(u64::to_string).collect();
    format!(
        "<dl class=\"provenance\">\n<dt>command</dt><dd><code>{}</code></dd>\n\
         <dt>seeds</dt><dd>{}</dd>\n<dt>lightlab</dt><dd>{}</dd>\n</dl>\n",
        escape(&report.command),
        escape(&seeds.join(", ")),
        VERSION
    )
}

fn viewer(report: &Report) -> String {
    let options: String = report
        .viewer
        .iter()
        .enumerate()
        .map(|(i, v)| format!("<option value=\"{i}\">{}</option>", escape(&v.label)))
        .collect();
    format!(
        "<section class=\"viewer\">\n<h2>Images</h2>\n<div class=\"controls\">\n\
         <label>left <select id=\"pick-a\">{options}</select></label>\n\
         <label>right <select id=\"pick-b\">{options}</select></label>\n\
         <label><input type=\"radio\" name=\"mode\" value=\"slider\" checked> slider</label>\n\
         <label><input type=\"radio\" name=\"mode\" value=\"flip\"> flip (space)</label>\n\
         <label>exposure <input id=\"exposure\" type=\"range\" min=\"-8\" max=\"8\" step=\"0.1\" value=\"0\">\
         <output id=\"exposure-value\">0.0</output></label>\n\
         <button id=\"zoom-fit\" type=\"button\">fit</button>\
         <button id=\"zoom-1\" type=\"button\">1:1</button>\
         <span id=\"zoom-value\"></span>\n</div>\n\
         <div id=\"stage\" class=\"stage\"><div id=\"frame\" class=\"frame\">\
         <canvas id=\"canvas-a\"></canvas><canvas id=\"canvas-b\"></canvas></div>\
         <div id=\"divider\" class=\"divider\"></div>\
         <div id=\"label-a\" class=\"tag tag-a\"></div><div id=\"label-b\" class=\"tag tag-b\"></div></div>\n\
         <input id=\"split\" class=\"split\" type=\"range\" min=\"0\" max=\"100\" step=\"0.1\" value=\"50\">\n\
         <p class=\"hint\">Wheel zooms about the cursor (pixels stay sharp), drag pans, the \
         slider under the image moves the split; in flip mode space or a click swaps.</p>\n\
         </section>\n"
    )
}

fn table_html(table: &Table) -> String {
    let mut out = String::from("<section>\n<table>\n");
    if !table.caption.is_empty() {
        out += &format!("<caption>{}</caption>\n", escape(&table.caption));
    }
    out += "<thead><tr>";
    for h in &table.header {
        out += &format!("<th>{}</th>", escape(h));
    }
    out += "</tr></thead>\n<tbody>\n";
    for row in &table.rows {
        out += "<tr>";
        for c in row {
            out += &format!("<td>{}</td>", escape(c));
        }
        out += "</tr>\n";
    }
    out + "</tbody>\n</table>\n</section>\n"
}

fn gallery_html(g: &Gallery) -> String {
    let mut out = format!("<section>\n<h2>{}</h2>\n", escape(&g.title));
    if !g.note.is_empty() {
        out += &format!("<p class=\"note\">{}</p>\n", escape(&g.note));
    }
    out += "<table class=\"gallery\">\n";
    if !g.columns.is_empty() {
        out += "<tr><th></th>";
        for c in &g.columns {
            out += &format!("<th>{}</th>", escape(c));
        }
        out += "</tr>\n";
    }
    for (label, files) in &g.rows {
        out += &format!("<tr><th>{}</th>", escape(label));
        for f in files {
            out += &format!(
                "<td><a href=\"{0}\"><img class=\"pixelated\" src=\"{0}\" alt=\"{1}\"></a></td>",
                escape(f),
                escape(label)
            );
        }
        out += "</tr>\n";
    }
    out + "</table>\n</section>\n"
}
