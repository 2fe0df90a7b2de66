//! The HTML page of a report: one self-contained `index.html` whose images
//! are files beside it, referenced relatively, so the directory can be
//! copied and opened offline. Divergent pixels are marked over the
//! difference overlay; hovering a mark shows its coordinates and the first
//! divergent operation, and links to its row in the table.

use crate::history::{History, HistoryEntry};
use crate::model::*;
use crate::plot::short_number;
use harness::verdict::Status;
use std::fmt::Write;

/// Escape text for HTML content and attribute values.
pub fn esc(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            _ => out.push(c),
        }
    }
    out
}

/// A duration in a readable unit: `85 ns`, `3.2 µs`, `14 ms`, `2.5 s`, `4m 10s`.
pub fn seconds(s: f64) -> String {
    if s <= 0.0 || !s.is_finite() {
        "–".into()
    } else if s < 1e-6 {
        format!("{:.0} ns", s * 1e9)
    } else if s < 1e-3 {
        format!("{:.1} µs", s * 1e6)
    } else if s < 1.0 {
        format!("{:.1} ms", s * 1e3)
    } else if s < 120.0 {
        format!("{s:.1} s")
    } else {
        format!("{}m {:02}s", (s / 60.0).floor(), (s % 60.0).round() as u64)
    }
}

fn opt_number(v: Option<f64>) -> String {
    v.map(short_number).unwrap_or_else(|| "–".into())
}

fn yes_no(v: Option<bool>) -> &'static str {
    match v {
        Some(true) => "<span class=ok>yes</span>",
        Some(false) => "<span class=bad>no</span>",
        None => "–",
    }
}

/// Append `<table>` and its header row: one `<th>` per column (HTML).
fn table_head<C: std::fmt::Display>(h: &mut String, columns: impl IntoIterator<Item = C>) {
    h.push_str("<table><tr>");
    for c in columns {
        let _ = write!(h, "<th>{c}</th>");
    }
    h.push_str("</tr>");
}

/// Append a table row of cells made by [`td`], [`td_n`] and [`td_code`].
fn row(h: &mut String, cells: &[String]) {
    h.push_str("<tr>");
    cells.iter().for_each(|c| h.push_str(c));
    h.push_str("</tr>");
}

/// A table cell holding `html`.
fn td(html: impl std::fmt::Display) -> String {
    format!("<td>{html}</td>")
}

/// A numeric table cell (right-aligned).
fn td_n(html: impl std::fmt::Display) -> String {
    format!("<td class=n>{html}</td>")
}

/// A table cell holding `text` as code.
fn td_code(text: &str) -> String {
    format!("<td><code>{}</code></td>", esc(text))
}

/// Anchor-safe id fragment of a label.
fn slug(s: &str) -> String {
    s.chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '-' })
        .collect()
}

const STYLE: &str = r#"
body{font-family:system-ui,-apple-system,"Segoe UI",Roboto,sans-serif;margin:0;color:#1d2430;background:#f6f7f9;line-height:1.45}
header{background:#1d2430;color:#fff;padding:18px 32px}
header h1{margin:0 0 4px;font-size:22px}
header .meta{color:#c9d1dc;font-size:13px}
header code{background:#2e3848;color:#fff}
nav{padding:8px 32px;background:#e9edf2;font-size:14px;position:sticky;top:0;z-index:3}
nav a{margin-right:14px;color:#1a4f8b;text-decoration:none}
main{padding:8px 32px 40px;max-width:1200px}
section{background:#fff;border:1px solid #dde2e8;border-radius:6px;padding:6px 20px 16px;margin:16px 0}
h2{font-size:19px;border-bottom:1px solid #e3e7ec;padding-bottom:4px}
h3{font-size:16px;margin:18px 0 6px}
table{border-collapse:collapse;font-size:13px;margin:6px 0}
th,td{border:1px solid #d5dbe2;padding:3px 8px;text-align:left;vertical-align:top}
th{background:#eef1f5}
tr:nth-child(even) td{background:#fafbfc}
td.n{text-align:right;font-variant-numeric:tabular-nums}
code{font-size:12px;background:#f1f3f5;padding:1px 4px;border-radius:3px}
.ok{color:#17803d;font-weight:600}.bad{color:#c62828;font-weight:600}.warn{color:#a15c00;font-weight:600}
.cards{display:flex;gap:12px;flex-wrap:wrap}
.card{border:1px solid #dde2e8;border-radius:6px;padding:8px 14px;min-width:150px;background:#fbfcfd}
.card b{display:block;font-size:22px}
.figs{display:grid;grid-template-columns:repeat(auto-fill,minmax(520px,1fr));gap:14px}
figure{margin:0}
figcaption{font-size:12px;color:#4a5563;margin-top:2px}
img.px{width:100%;max-width:1024px;image-rendering:pixelated;border:1px solid #c9d0d8;display:block}
img.legend{width:100%;max-width:512px;display:block}
.pixmap{position:relative}
.pixmap svg{position:absolute;left:0;top:0;width:100%;height:100%}
.pixmap rect.mark{fill:none;stroke:#ffb000;stroke-width:1.2;vector-effect:non-scaling-stroke}
.pixmap rect.mark:hover{stroke:#000;stroke-width:3}
.swatch{display:inline-block;width:12px;height:12px;border:1px solid #888;vertical-align:middle}
details summary{cursor:pointer;margin:6px 0}
.problems li{color:#a15c00}
tr:target td{background:#fff3c4}
"#;

/// Checks, once the page has loaded, that every image decoded, and records
/// the counts on `<body>` (`data-images-loaded`, `data-images-total`) for
/// tests and readers.
const IMAGE_CHECK: &str = r#"
window.addEventListener('load',function(){var imgs=document.querySelectorAll('img'),ok=0;
imgs.forEach(function(i){if(i.complete&&i.naturalWidth>0){ok++}else{i.classList.add('broken');i.alt='missing: '+i.getAttribute('src')}});
document.body.setAttribute('data-images-loaded',ok);document.body.setAttribute('data-images-total',imgs.length);});
function openTarget(){var t=location.hash&&document.getElementById(decodeURIComponent(location.hash.slice(1)));
for(var e=t;e;e=e.parentElement){if(e.tagName==='DETAILS'){e.open=true}}if(t){t.scrollIntoView()}}
window.addEventListener('hashchange',openTarget);window.addEventListener('load',openTarget);
"#;

/// Render the page for `report`, with the trend table from `history`
/// (which should already hold this run's entry).
pub fn render(report: &Report, history: &History) -> String {
    let mut h = String::new();
    let m = &report.meta;
    let _ = write!(
        h,
        "<!DOCTYPE html>\n<html lang=en><head><meta charset=utf-8><meta name=viewport content=\"width=device-width\">\
         <title>Divergence report {}</title><style>{STYLE}</style><script>{IMAGE_CHECK}</script></head><body>\n",
        esc(&m.started_at)
    );
    let _ = writeln!(
        h,
        "<header><h1>Float316 raymarcher: nightly divergence report</h1><div class=meta>{} · commit <code>{}</code>{} · {} · {} CPUs · harness {} · report schema {}</div></header>",
        esc(&m.started_at),
        esc(&m.git_commit),
        if m.git_dirty { " (uncommitted changes)" } else { "" },
        seconds(m.duration_s),
        m.cpus,
        esc(&m.harness_version),
        report.schema_version
    );
    h.push_str(
        "<nav><a href=#summary>Summary</a><a href=#levels>Levels</a><a href=#testfloat>TestFloat</a><a href=#renders>Renders</a><a href=#pairs>Image pairs</a>\
         <a href=#cost>Cost map</a><a href=#speed>Speed vs error</a><a href=#stability>Stability</a><a href=#bench>Bench</a><a href=#scenes>Scenes</a><a href=#trend>Trend</a></nav>\n<main>\n",
    );
    summary(&mut h, report);
    levels(&mut h, report);
    testfloat(&mut h, report);
    renders(&mut h, report);
    pairs(&mut h, report);
    cost_map(&mut h, report);
    speed(&mut h, report);
    stability(&mut h, report);
    bench(&mut h, report);
    scenes(&mut h, report);
    trend(&mut h, history);
    h.push_str("</main></body></html>\n");
    h
}

fn summary(h: &mut String, r: &Report) {
    let opened = r.implementations.iter().filter(|i| i.available).count();
    let pixel_pairs_differing = r
        .image_pairs
        .iter()
        .filter(|p| p.differing_pixels > 0)
        .count();
    let v = &r.verdict;
    let beyond = v.beyond_policy();
    let missing = v.not_compared.len();
    let card = |h: &mut String, value: String, label: &str, class: &str| {
        let _ = write!(
            h,
            "<div class=card><b class={class}>{value}</b>{label}</div>"
        );
    };
    h.push_str("<section id=summary><h2>Summary</h2><div class=cards>");
    let (status, class) = match v.status() {
        Status::Agreed => ("passed", "ok"),
        Status::Diverged => ("DIVERGED", "bad"),
        Status::Incomplete => ("INCOMPLETE", "bad"),
    };
    card(h, status.into(), "verdict", class);
    card(
        h,
        format!("{opened}/{}", r.implementations.len()),
        "implementations opened",
        if opened == r.implementations.len() {
            ""
        } else {
            "warn"
        },
    );
    card(
        h,
        format!("{beyond}/{}", v.compared.len()),
        "comparisons beyond policy (levels, images, self-test)",
        if beyond == 0 { "ok" } else { "bad" },
    );
    card(
        h,
        missing.to_string(),
        "not compared (failed, unavailable)",
        if missing == 0 { "ok" } else { "bad" },
    );
    card(
        h,
        format!("{pixel_pairs_differing}/{}", r.image_pairs.len()),
        "image pairs with differing pixels",
        "",
    );
    match &r.selftest {
        Some(t) => card(
            h,
            if t.passed { "pass" } else { "FAIL" }.into(),
            "self-test",
            if t.passed { "ok" } else { "bad" },
        ),
        None => card(h, "–".into(), "self-test not run", "warn"),
    }
    card(h, seconds(r.meta.duration_s), "run duration", "");
    h.push_str("</div>\n");
    let failing: Vec<String> = v
        .compared
        .iter()
        .filter_map(|c| {
            c.beyond_policy
                .as_ref()
                .map(|why| format!("{}: {why}", c.what))
        })
        .chain(
            v.not_compared
                .iter()
                .map(|n| format!("{} {}: {}", n.missing, n.what, n.why)),
        )
        .collect();
    if !failing.is_empty() {
        h.push_str("<h3>What fails the run</h3><ul class=problems>");
        for line in &failing {
            let _ = write!(h, "<li>{}</li>", esc(line));
        }
        h.push_str("</ul>");
    }
    if !r.problems.is_empty() {
        h.push_str("<h3>Problems (steps that did not run or failed)</h3><ul class=problems>");
        for p in &r.problems {
            let _ = write!(h, "<li>{}</li>", esc(p));
        }
        h.push_str("</ul>");
    }
    h.push_str("<h3>Implementations</h3>");
    table_head(h, ["name", "available", "opening", "note"]);
    for i in &r.implementations {
        row(
            h,
            &[
                td_code(&i.name),
                td(yes_no(Some(i.available))),
                td(seconds(i.open_s)),
                td(esc(i.note.as_deref().unwrap_or(""))),
            ],
        );
    }
    h.push_str("</table>");
    if let Some(t) = &r.selftest {
        let _ = write!(
            h,
            "<details><summary>Self-test: {} checks</summary><pre>",
            t.lines.len()
        );
        for l in &t.lines {
            let _ = writeln!(h, "{}", esc(l));
        }
        h.push_str("</pre></details>");
    }
    h.push_str("<h3>Steps</h3>");
    table_head(h, ["step", "time"]);
    for s in &r.meta.steps {
        row(h, &[td(esc(&s.step)), td_n(seconds(s.seconds))]);
    }
    h.push_str("</table></section>\n");
}

fn levels(h: &mut String, r: &Report) {
    h.push_str(
        "<section id=levels><h2>Level comparisons</h2><p>Float316 implementations must agree bit for bit (any difference is a divergence); \
         float implementations are measured against <code>ref-f64</code> (error figures, reported not hidden).</p>",
    );
    table_head(
        h,
        [
            "level",
            "scope",
            "A",
            "B",
            "policy",
            "cases",
            "divergences",
            "mean |err|",
            "max |err|",
        ],
    );
    for c in &r.comparisons {
        let class = if c.divergences == 0 {
            "ok"
        } else if c.policy == crate::BIT_EXACT {
            "bad"
        } else {
            "warn"
        };
        row(
            h,
            &[
                td(esc(&c.level)),
                td(esc(&c.scope)),
                td_code(&c.a),
                td_code(&c.b),
                td(esc(&c.policy)),
                td_n(c.cases),
                format!("<td class=\"n {class}\">{}</td>", c.divergences),
                td_n(opt_number(c.error.map(|e| e.mean_abs))),
                td_n(opt_number(c.error.map(|e| e.max_abs))),
            ],
        );
    }
    h.push_str("</table>");
    let with_examples: Vec<&Comparison> = r
        .comparisons
        .iter()
        .filter(|c| !c.examples.is_empty())
        .collect();
    if !with_examples.is_empty() {
        h.push_str("<h3>First divergent cases</h3>");
        for c in with_examples {
            let _ = write!(
                h,
                "<details><summary>{} {}: <code>{}</code> vs <code>{}</code> ({} shown)</summary>",
                esc(&c.level),
                esc(&c.scope),
                esc(&c.a),
                esc(&c.b),
                c.examples.len()
            );
            table_head(
                h,
                ["case", "A", "B", "first divergent operation", "reproduce"],
            );
            for e in &c.examples {
                row(
                    h,
                    &[
                        td_code(&e.case),
                        td(esc(&e.a)),
                        td(esc(&e.b)),
                        td(esc(e.first_op.as_deref().unwrap_or("–"))),
                        e.repro.as_deref().map(td_code).unwrap_or_else(|| td("")),
                    ],
                );
            }
            h.push_str("</table></details>");
        }
    }
    h.push_str("</section>\n");
}

/// The TestFloat-style cases per operation: levels 1 and 2 side by side,
/// where they ran and their bit-exact divergences (the comparisons are
/// rows of Levels).
fn testfloat(h: &mut String, r: &Report) {
    h.push_str(
        "<section id=testfloat><h2>TestFloat-style cases</h2><p>Every operation's cases in the manner of Berkeley TestFloat \
         (sign x exponent table x mantissa pattern table; level 2 adds weighted random pairs; docs/coverage.md), \
         compared bit for bit with the first implementation listed.</p>",
    );
    if r.testfloat.is_empty() {
        h.push_str("<p>No TestFloat step in this run.</p></section>\n");
        return;
    }
    let mut ops: Vec<&str> = Vec::new();
    for c in &r.testfloat {
        if !ops.contains(&c.op.as_str()) {
            ops.push(&c.op);
        }
    }
    table_head(
        h,
        [
            "operation",
            "level 1 cases",
            "level 1 divergences",
            "level 2 cases",
            "level 2 divergences",
            "implementations",
        ],
    );
    for op in ops {
        let at = |level: u8| r.testfloat.iter().find(|c| c.op == op && c.level == level);
        let mut cells = vec![td_code(op)];
        for level in [1, 2] {
            match at(level) {
                Some(c) => {
                    let class = if c.divergences == 0 { "ok" } else { "bad" };
                    cells.push(td_n(c.cases));
                    cells.push(format!("<td class=\"n {class}\">{}</td>", c.divergences));
                }
                None => cells.extend([td("–"), td("–")]),
            }
        }
        let names = at(2)
            .or(at(1))
            .map(|c| c.implementations.join(", "))
            .unwrap_or_default();
        cells.push(td(esc(&names)));
        row(h, &cells);
    }
    h.push_str("</table></section>\n");
}

fn renders(h: &mut String, r: &Report) {
    h.push_str("<section id=renders><h2>Renders</h2><div class=figs>");
    for x in &r.renders {
        let spec = match x.identical_to_spec {
            Some(true) => " · identical to the spec image",
            Some(false) => " · differs from the spec image",
            None => "",
        };
        let _ = write!(
            h,
            "<figure><img class=px src=\"{}\" alt=\"render of {}\"><figcaption><code>{}</code>: {} for {} pixels ({} per pixel{}){spec}</figcaption></figure>",
            esc(&x.image),
            esc(&x.label),
            esc(&x.label),
            seconds(x.render_s),
            x.pixels,
            seconds(per_pixel(x.render_s, x.pixels)),
            x.vm_instructions
                .map(|n| format!(", {} VM instructions per pixel", short_number(n as f64 / x.pixels.max(1) as f64)))
                .unwrap_or_default(),
        );
    }
    h.push_str("</div></section>\n");
}

fn per_pixel(total_s: f64, pixels: u64) -> f64 {
    if pixels == 0 {
        0.0
    } else {
        total_s / pixels as f64
    }
}

fn pairs(h: &mut String, r: &Report) {
    h.push_str(
        "<section id=pairs><h2>Image pairs</h2><p>Overlay: the first image faded, pixels white in A and black in B in \
         <span class=swatch style=background:rgb(230,0,60)></span> red, black in A and white in B in \
         <span class=swatch style=background:rgb(0,90,230)></span> blue. Listed divergent pixels are boxed; hover a box for the pixel and its first divergent operation, click it for its row.</p>",
    );
    for p in &r.image_pairs {
        let id = slug(&format!("{}-vs-{}", p.a, p.b));
        let pct = 100.0 * p.differing_pixels as f64 / p.pixels.max(1) as f64;
        let class = if p.differing_pixels == 0 { "ok" } else { "bad" };
        let shades = p
            .differing_shades
            .map(|n| format!(", {n} shades differ"))
            .unwrap_or_default();
        let _ = write!(
            h,
            "<details id=\"{id}\"{}><summary><b><code>{}</code> vs <code>{}</code></b>: <span class={class}>{} of {} pixels differ ({pct:.3}%)</span>{shades}</summary>",
            if p.differing_pixels > 0 { " open" } else { "" },
            esc(&p.a),
            esc(&p.b),
            p.differing_pixels,
            p.pixels
        );
        h.push_str("<div class=figs><figure><div class=pixmap>");
        let _ = write!(
            h,
            "<img class=px src=\"{}\" alt=\"overlay {} vs {}\">",
            esc(&p.overlay),
            esc(&p.a),
            esc(&p.b)
        );
        marks(h, &id, p);
        h.push_str("</div><figcaption>difference overlay</figcaption></figure>");
        if let Some(heat) = &p.heat {
            let _ = write!(
                h,
                "<figure><img class=px src=\"{}\" alt=\"shade error heat map\"><img class=legend src=\"{}\" alt=\"colour bar\"><figcaption>|shade A − shade B| per pixel, log scale, black = identical; mean {}, p50 {}, p95 {}, p99 {}, max {}</figcaption></figure>",
                esc(&heat.image),
                esc(&heat.legend),
                short_number(heat.mean_abs),
                short_number(heat.percentiles_abs[0]),
                short_number(heat.percentiles_abs[1]),
                short_number(heat.percentiles_abs[2]),
                short_number(heat.max_abs)
            );
        }
        h.push_str("</div>");
        if let Some(e) = &p.explanation {
            explanation(h, e);
        }
        if !p.divergences.is_empty() {
            let _ = write!(
                h,
                "<p>First divergent operation: {}</p><details class=pixels><summary>{} listed divergent pixels: first divergent operation and repro command of each (click a box on the overlay for its row)</summary>",
                esc(&p.localization),
                p.divergences.len()
            );
            table_head(
                h,
                ["x", "y", "A", "B", "first divergent operation", "reproduce"],
            );
            for d in &p.divergences {
                let cells = [
                    td_n(d.x),
                    td_n(d.y),
                    td(pixel_text(d.a_white, d.a_shade)),
                    td(pixel_text(d.b_white, d.b_shade)),
                    td(esc(d
                        .first_op
                        .as_deref()
                        .or(d.explained.as_deref())
                        .unwrap_or("not localizable (see above)"))),
                    td_code(&d.repro),
                ];
                // The row is the target of its mark's link.
                let _ = write!(h, "<tr id=\"{id}-{}-{}\">{}</tr>", d.x, d.y, cells.concat());
            }
            h.push_str("</table></details>");
            if p.unlisted > 0 {
                let _ = write!(h, "<p>{} more divergent pixels not listed.</p>", p.unlisted);
            }
        }
        h.push_str("</details>\n");
    }
    h.push_str("</section>\n");
}

/// Why a lower precision differs from the oracle: classes, decisions,
/// root causes and the class map.
fn explanation(h: &mut String, e: &PairExplanation) {
    let _ = write!(
        h,
        "<h4>Why they differ</h4><p>Explained by <code>{}</code>: {}, in {} s; {}.</p><div class=figs>",
        esc(&e.explained_by),
        esc(&e.inputs),
        short_number(e.seconds),
        esc(&e.holds)
    );
    table_head(h, ["class", "pixels"]);
    for c in &e.classes {
        row(h, &[td(esc(&c.name)), td_n(c.count)]);
    }
    for d in &e.decisions {
        row(
            h,
            &[
                td(format!("&nbsp;&nbsp;at {}", esc(&d.name))),
                td_n(d.count),
            ],
        );
    }
    h.push_str("</table>");
    if !e.class_map.is_empty() {
        let key: Vec<String> = e
            .colours
            .iter()
            .map(|c| {
                format!(
                    "<span style=\"color:#{:06x}\">■</span> {}",
                    c.count,
                    esc(&c.name)
                )
            })
            .collect();
        let _ = write!(
            h,
            "<figure><img class=px src=\"{}\" alt=\"pixels by class\"><figcaption>explained pixels by class: {}</figcaption></figure>",
            esc(&e.class_map),
            key.join(", ")
        );
    }
    h.push_str("</div>");
    table_head(
        h,
        ["root cause (largest contributor)", "pixels", "mean share"],
    );
    for c in &e.causes {
        row(
            h,
            &[
                td_code(&c.site),
                td_n(c.pixels),
                td_n(format!("{:.0}%", 100.0 * c.mean_share)),
            ],
        );
    }
    h.push_str("</table>");
    if !e.examples.is_empty() {
        h.push_str("<ul>");
        for line in &e.examples {
            let _ = write!(h, "<li>{}</li>", esc(line));
        }
        h.push_str("</ul>");
    }
}

fn pixel_text(white: bool, shade: Option<f64>) -> String {
    let bit = if white { "white" } else { "black" };
    match shade {
        Some(s) => format!("{bit} ({s:.6})"),
        None => bit.into(),
    }
}

/// The hover layer over an overlay: one box per listed divergent pixel.
fn marks(h: &mut String, id: &str, p: &ImagePair) {
    if p.divergences.is_empty() {
        return;
    }
    // The marks use the overlay's pixel grid.
    let (w, hgt) = (p.width, p.height);
    let _ = write!(
        h,
        "<svg viewBox=\"0 0 {w} {hgt}\" preserveAspectRatio=none>"
    );
    for d in &p.divergences {
        let tip = format!(
            "pixel ({}, {}): {} vs {}\n{}",
            d.x,
            d.y,
            pixel_text(d.a_white, d.a_shade),
            pixel_text(d.b_white, d.b_shade),
            d.first_op.as_deref().unwrap_or(&p.localization)
        );
        let _ = write!(
            h,
            "<a href=\"#{id}-{}-{}\"><rect class=mark x=\"{}\" y=\"{}\" width=5 height=5><title>{}</title></rect></a>",
            d.x,
            d.y,
            d.x as f64 - 2.0,
            d.y as f64 - 2.0,
            esc(&tip)
        );
    }
    h.push_str("</svg>");
}

fn cost_map(h: &mut String, r: &Report) {
    h.push_str("<section id=cost><h2>Jack program: VM instructions per pixel</h2>");
    match &r.cost_map {
        Some(c) => {
            let _ = write!(
                h,
                "<div class=figs><figure><img class=px src=\"{}\" alt=\"cost map\"><img class=legend src=\"{}\" alt=\"colour bar\">\
                 <figcaption>Hack VM instructions spent on each pixel: min {}, mean {}, max {}</figcaption></figure></div>",
                esc(&c.image),
                esc(&c.legend),
                c.min,
                short_number(c.mean),
                c.max
            );
        }
        None => h.push_str("<p class=warn>The Jack program did not run; no cost map.</p>"),
    }
    h.push_str("</section>\n");
}

/// The cells the speed and bench tables share: VM instructions per pixel,
/// mean and max |shade error| against `ref-f64`, pixel flips.
fn cost_and_error(
    vm_instructions: Option<f64>,
    mean_error: Option<f64>,
    max_error: Option<f64>,
    flips: u64,
) -> [String; 4] {
    [
        td_n(opt_number(vm_instructions)),
        td_n(opt_number(mean_error)),
        td_n(opt_number(max_error)),
        td_n(flips),
    ]
}

fn speed(h: &mut String, r: &Report) {
    let s = &r.speed_error;
    h.push_str("<section id=speed><h2>Speed against error</h2>");
    if !s.plot.is_empty() {
        let _ = write!(
            h,
            "<img src=\"{}\" alt=\"speed against error plot\" style=max-width:100%>",
            esc(&s.plot)
        );
    }
    match &s.cheapest_spec_identical {
        Some(c) => {
            let _ = write!(h, "<p>Cheapest precision variant whose dithered image is identical to the spec's: <b>{}</b>.</p>", esc(c));
        }
        None => h.push_str("<p class=warn>No precision variant reproduced the spec's image.</p>"),
    }
    table_head(
        h,
        [
            "implementation / variant",
            "time per pixel",
            "VM instr. per pixel",
            "mean |shade err|",
            "max |shade err|",
            "pixel flips vs ref-f64",
            "identical to spec",
        ],
    );
    for p in &s.points {
        let mut cells = vec![td_code(&p.label), td_n(seconds(p.time_per_pixel_s))];
        cells.extend(cost_and_error(
            p.vm_instructions_per_pixel,
            p.mean_shade_error,
            p.max_shade_error,
            p.pixel_flips,
        ));
        cells.push(td(yes_no(p.identical_to_spec)));
        row(h, &cells);
    }
    h.push_str("</table></section>\n");
}

fn stability(h: &mut String, r: &Report) {
    h.push_str(
        "<section id=stability><h2>Numerical stability: hard cases</h2><p>Per category of the nightly sets (the op vectors' hard-case catalogue, the scene's hard places for SDF queries and pixels), how many vectors ended as a value (V), Sys.error (E), hang (H) or out of domain (D) on each implementation; \
         for Float316 implementations, ≠ counts answers that differ from <code>ref-f316</code> bit for bit. The worst error is the largest relative error against <code>ref-f64</code> over answers that are values on both sides; its repro file lies in this report's directory.</p>",
    );
    if r.stability.is_empty() {
        h.push_str("<p class=warn>No stability rows: no nightly set was answered.</p></section>\n");
        return;
    }
    let impls: std::collections::BTreeSet<&String> =
        r.stability.iter().flat_map(|s| s.outcomes.keys()).collect();
    let columns = ["set", "category", "vectors"].map(String::from);
    let impl_columns = impls.iter().map(|i| format!("<code>{}</code>", esc(i)));
    table_head(
        h,
        columns
            .into_iter()
            .chain(impl_columns)
            .chain(["worst error vs f64".to_string()]),
    );
    for s in &r.stability {
        let mut cells = vec![td(esc(&s.set)), td(esc(&s.category)), td_n(s.vectors)];
        cells.extend(impls.iter().map(|i| td(outcome_tally(s.outcomes.get(*i)))));
        cells.push(td(worst_error(s.worst.as_ref())));
        row(h, &cells);
    }
    h.push_str("</table></section>\n");
}

/// One implementation's outcomes in a stability row.
fn outcome_tally(tally: Option<&OutcomeTally>) -> String {
    let Some(t) = tally else {
        return "not run".into();
    };
    let mut text = format!(
        "V {} · E {} · H {} · D {}",
        t.value, t.sys_error, t.hang, t.out_of_domain
    );
    match t.diverging {
        Some(0) => text.push_str(" · <span class=ok>≠ 0</span>"),
        Some(n) => {
            let _ = write!(text, " · <span class=bad>≠ {n}</span>");
        }
        None => {}
    }
    text
}

/// The worst error of a stability row, with its repro command.
fn worst_error(worst: Option<&WorstError>) -> String {
    let Some(w) = worst else {
        return "no value on both sides".into();
    };
    let mut text = format!(
        "{} rel, {} abs: <code>{}</code> on <code>{}</code> ({}): {}",
        short_number(w.rel),
        short_number(w.abs),
        esc(&w.implementation),
        esc(&w.case),
        esc(&w.vector),
        esc(&w.answers)
    );
    if let Some(repro) = &w.repro {
        let _ = write!(text, "<br><code>{}</code>", esc(repro));
    }
    text
}

fn bench(h: &mut String, r: &Report) {
    h.push_str("<section id=bench><h2>Benchmarks</h2>");
    table_head(
        h,
        [
            "implementation",
            "set-up",
            "full image",
            "per pixel",
            "pixels/s",
            "VM instr. per pixel",
            "mean |err|",
            "max |err|",
            "flips",
        ],
    );
    for b in &r.bench {
        let mut cells = vec![
            td_code(&b.implementation),
            td_n(seconds(b.setup_s)),
            td_n(seconds(b.image_s)),
            td_n(seconds(b.per_pixel_s)),
            td_n(short_number(b.pixels_per_s())),
        ];
        cells.extend(cost_and_error(
            b.vm_instructions_per_pixel,
            b.mean_shade_error,
            b.max_shade_error,
            b.pixel_flips,
        ));
        row(h, &cells);
    }
    h.push_str("</table></section>\n");
}

/// The described scenes: what each uses and never reaches, and its cost
/// per pixel on each implementation (their comparisons are in Levels).
fn scenes(h: &mut String, r: &Report) {
    h.push_str("<section id=scenes><h2>Scenes</h2>");
    if r.scenes.is_empty() {
        h.push_str("<p>No scene step in this run.</p></section>\n");
        return;
    }
    let list = |items: &[String]| esc(&items.join(", "));
    for s in &r.scenes {
        let reached: Vec<String> = s
            .reached
            .iter()
            .map(|(op, n)| format!("{op} {n}"))
            .collect();
        let _ = write!(
            h,
            "<h3><code>{}</code> ({})</h3><ul><li>shapes: {}</li><li>Float316 operations: {}</li>\
             <li>reached over {} traced pixels: {}</li><li>never reached: {}</li><li>domains never reached: {}</li>",
            esc(&s.name),
            esc(&s.file),
            list(&s.shapes),
            list(&s.operations),
            s.traced_pixels,
            esc(&reached.join(", ")),
            list(&s.never_reached),
            list(&s.domains_never_reached),
        );
        for u in &s.unsupported {
            let _ = write!(h, "<li>{}</li>", esc(u));
        }
        h.push_str("</ul>");
        table_head(
            h,
            [
                "implementation",
                "set-up",
                "full image",
                "pixels",
                "per pixel",
            ],
        );
        for c in &s.costs {
            row(
                h,
                &[
                    td_code(&c.implementation),
                    td_n(seconds(c.setup_s)),
                    td_n(seconds(c.render_s)),
                    td_n(c.pixels),
                    td_n(seconds(c.per_pixel_s)),
                ],
            );
        }
        h.push_str("</table>");
        scene_outcomes(h, &s.outcomes);
        if let Some(cpu) = s.cpu_s {
            let _ = write!(
                h,
                "<p>The step's CPU time on this scene: {} (every thread).</p>",
                duration(cpu)
            );
        }
        if let Some(j) = &s.jack {
            scene_jack(h, j);
        }
        if let Some(base) = &s.tuned_from {
            tuned_saving(h, s, base, &r.scenes);
        }
        if !s.pictures.is_empty() {
            h.push_str("<div class=figs>");
            for p in &s.pictures {
                let _ = write!(
                    h,
                    "<figure><img class=px src=\"{}\" alt=\"{}\"><figcaption>{}</figcaption></figure>",
                    esc(&p.image),
                    esc(&p.caption),
                    esc(&p.caption)
                );
            }
            h.push_str("</div>");
        }
    }
    h.push_str("</section>\n");
}

/// A tuned scene's saving against the untuned scene `base` of the same
/// night: generated-Jack VM instructions per pixel and over the image.
fn tuned_saving(h: &mut String, tuned: &SceneRow, base: &str, scenes: &[SceneRow]) {
    let untuned = scenes
        .iter()
        .find(|s| s.name == base && s.tuned_from.is_none())
        .and_then(|s| s.jack.as_ref());
    match (untuned, &tuned.jack) {
        (Some(u), Some(t)) => {
            let saved = u.mean - t.mean;
            let _ = write!(
                h,
                "<p>Tuned from <code>{}</code>: {} VM instructions per pixel against {} untuned, \
                 {} saved per pixel ({:.3}%), {} over the image; on the official desktop emulator {} against {}.</p>",
                esc(base),
                short_number(t.mean),
                short_number(u.mean),
                short_number(saved),
                100.0 * saved / u.mean.max(1.0),
                short_number(u.whole_image_instructions as f64 - t.whole_image_instructions as f64),
                duration(t.desktop_s),
                duration(u.desktop_s),
            );
        }
        _ => {
            let _ = write!(
                h,
                "<p>Tuned from <code>{}</code>, whose generated program was not measured in this run: no saving to show.</p>",
                esc(base)
            );
        }
    }
}

/// How each implementation's answers for a scene ended, and whether the
/// Float316 ones agree on how many are out of domain.
fn scene_outcomes(h: &mut String, outcomes: &[SceneOutcomes]) {
    if outcomes.is_empty() {
        return;
    }
    h.push_str(
        "<p>Outcomes: answers out of the modelled domain (each stopped at the one Float316 operation that left it), \
         <code>Sys.error</code> and hangs, per implementation and level.</p>",
    );
    table_head(
        h,
        [
            "implementation",
            "level",
            "answers",
            "out of domain",
            "Sys.error",
            "hang",
        ],
    );
    for o in outcomes {
        row(
            h,
            &[
                td_code(&o.implementation),
                td(esc(&o.level)),
                td_n(o.cases),
                td_n(o.out_of_domain),
                td_n(o.sys_error),
                td_n(o.hang),
            ],
        );
    }
    h.push_str("</table>");
    for level in ["pixels", "sdf"] {
        let counts: std::collections::BTreeSet<(u64, u64)> = outcomes
            .iter()
            .filter(|o| o.level == level && is_float316(&o.implementation))
            .map(|o| (o.cases, o.out_of_domain))
            .collect();
        if counts.len() > 1 {
            let _ = write!(
                h,
                "<p class=warn>The Float316 implementations disagree on how many {level} answers are out of domain.</p>"
            );
        }
    }
}

/// Whether a scene leg computes in Float316 (`ref-f316`, `gpu-f316`, the
/// generated Jack program).
fn is_float316(label: &str) -> bool {
    label.ends_with("f316") || label.starts_with("jack")
}

/// The cost of a scene's generated Jack program.
fn scene_jack(h: &mut String, j: &SceneJackCost) {
    let fits = |words: u64| {
        if words <= j.rom_words {
            "fits"
        } else {
            "does not fit"
        }
    };
    let measured = if j.step == 1 {
        "every pixel".to_string()
    } else {
        format!("one pixel in each {0}x{0} block", j.step)
    };
    let main = j.main_s.map_or_else(
        || "Main.main did not finish".to_string(),
        |s| format!("Main.main measured at {} on one thread", duration(s)),
    );
    let _ = write!(
        h,
        "<p>Generated Jack program, {} measured ({} pixels): \
         <b>{:.0}</b> VM instructions per pixel (mean), max {}; the whole image {} VM instructions: \
         about <b>{}</b> on the official desktop VM emulator at 1.4 M/s ({} by the hand-written seed program's \
         9 h 45 min there); on ours {}, {} with the pixels in parallel. {} VM commands: about {} Hack ROM words in line ({} the {}), \
         {} with shared call/return/compare routines ({}).</p>",
        measured,
        j.pixels_measured,
        j.mean,
        j.max,
        j.whole_image_instructions,
        duration(j.desktop_s),
        duration(j.desktop_seed_scale_s),
        main,
        duration(j.ours_s),
        j.vm_commands,
        j.rom_textbook,
        fits(j.rom_textbook),
        j.rom_words,
        j.rom_shared,
        fits(j.rom_shared),
    );
}

/// `s` seconds as `9 h 45 min`, `3 min 20 s` or `4.2 s`.
pub fn duration(s: f64) -> String {
    if s >= 3600.0 {
        let m = (s / 60.0).round() as u64;
        format!("{} h {:02} min", m / 60, m % 60)
    } else if s >= 60.0 {
        let t = s.round() as u64;
        format!("{} min {:02} s", t / 60, t % 60)
    } else {
        format!("{s:.1} s")
    }
}

/// Most recent runs shown in the trend table.
const TREND_ROWS: usize = 30;

fn trend(h: &mut String, history: &History) {
    h.push_str("<section id=trend><h2>Trend</h2>");
    if history.unreadable > 0 {
        let _ = write!(
            h,
            "<p class=warn>{} unreadable history lines skipped.</p>",
            history.unreadable
        );
    }
    let recent: Vec<&HistoryEntry> = history.entries.iter().rev().take(TREND_ROWS).collect();
    // Columns: the implementations (not variants) of the latest run.
    let labels: Vec<&String> = recent
        .first()
        .map(|e| {
            e.seconds_per_pixel
                .keys()
                .filter(|k| !k.contains('/'))
                .collect()
        })
        .unwrap_or_default();
    let columns = [
        "date",
        "commit",
        "duration",
        "bit-exact divergences",
        "differing pixels",
        "problems",
    ]
    .map(String::from);
    let label_columns = labels
        .iter()
        .map(|l| format!("<code>{}</code><br>flips · per pixel", esc(l)));
    table_head(h, columns.into_iter().chain(label_columns));
    for e in &recent {
        let pixels: u64 = e.pixel_divergences.values().sum();
        let mut cells = vec![
            td(esc(&e.date)),
            td_code(e.commit.get(..10).unwrap_or(&e.commit)),
            td_n(seconds(e.duration_s)),
            td_n(e.divergences),
            td_n(pixels),
            td_n(e.problems),
        ];
        cells.extend(labels.iter().map(|l| {
            let flips = e
                .errors
                .get(*l)
                .map(|x| x.flips.to_string())
                .unwrap_or_else(|| "–".into());
            let speed = e
                .seconds_per_pixel
                .get(*l)
                .map(|s| seconds(*s))
                .unwrap_or_else(|| "–".into());
            td_n(format!("{flips} · {speed}"))
        }));
        row(h, &cells);
    }
    h.push_str("</table></section>\n");
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_explained_pair_shows_classes_causes_and_each_pixel() {
        let mut r = Report::new(RunMeta::default());
        r.image_pairs.push(ImagePair {
            a: "ref-f64".into(),
            b: "ref-f316".into(),
            differing_pixels: 1,
            divergences: vec![PixelDivergence {
                explained: Some(
                    "threshold flip; root cause inv_sqrt in pixel(*,*) > normalize (90%)".into(),
                ),
                ..PixelDivergence::default()
            }],
            explanation: Some(PairExplanation {
                explained_by: "ref-f316".into(),
                holds: "ref-f316 is the explained implementation".into(),
                inputs: "every pixel whose dithered bit differs (1)".into(),
                classes: vec![NamedCount {
                    name: "threshold flip".into(),
                    count: 1,
                }],
                causes: vec![CauseRow {
                    site: "inv_sqrt in pixel(*,*) > normalize".into(),
                    pixels: 1,
                    mean_share: 0.9,
                }],
                class_map: "images/classes.png".into(),
                colours: vec![NamedCount {
                    name: "threshold flip".into(),
                    count: 0xffd200,
                }],
                ..PairExplanation::default()
            }),
            ..ImagePair::default()
        });
        let page = render(&r, &History::default());
        assert!(page.contains("<h4>Why they differ</h4><p>Explained by <code>ref-f316</code>"));
        assert!(page.contains("<tr><td>threshold flip</td><td class=n>1</td></tr>"));
        assert!(page.contains("<td><code>inv_sqrt in pixel(*,*) &gt; normalize</code></td><td class=n>1</td><td class=n>90%</td>"));
        assert!(page.contains("<span style=\"color:#ffd200\">■</span> threshold flip"));
        assert!(page.contains(
            "<td>threshold flip; root cause inv_sqrt in pixel(*,*) &gt; normalize (90%)</td>"
        ));
        assert!(!page.contains("not localizable (see above)"));
    }

    #[test]
    fn durations_read_as_hours_minutes_or_seconds() {
        assert_eq!(duration(35_100.0), "9 h 45 min");
        assert_eq!(duration(200.0), "3 min 20 s");
        assert_eq!(duration(4.24), "4.2 s");
    }

    /// The outcomes table, and a warning when the Float316 legs (not the
    /// float ones, which answer values there) count differently.
    #[test]
    fn scene_outcomes_warn_when_the_float316_legs_disagree() {
        let o = |implementation: &str, out_of_domain| SceneOutcomes {
            implementation: implementation.into(),
            level: "pixels".into(),
            cases: 10,
            out_of_domain,
            ..SceneOutcomes::default()
        };
        let mut h = String::new();
        scene_outcomes(
            &mut h,
            &[o("ref-f64", 0), o("ref-f316", 3), o("gpu-f316", 3)],
        );
        assert!(
            h.contains("<td class=n>3</td>") && !h.contains("disagree"),
            "{h}"
        );
        let mut h = String::new();
        scene_outcomes(&mut h, &[o("ref-f316", 3), o("jack-generated", 2)]);
        assert!(h.contains("disagree on how many pixels answers"), "{h}");
    }

    /// A tuned scene's row says what it saves against its untuned scene's
    /// row of the same night, and says so when that row is missing.
    #[test]
    fn a_tuned_scene_shows_its_saving() {
        let jack = |mean, whole| SceneJackCost {
            mean,
            whole_image_instructions: whole,
            desktop_s: whole as f64 / 1.4e6,
            ..SceneJackCost::default()
        };
        let untuned = SceneRow {
            name: "seed".into(),
            jack: Some(jack(200.0, 2_000)),
            ..SceneRow::default()
        };
        let tuned = SceneRow {
            name: "seed-tuned".into(),
            jack: Some(jack(150.0, 1_500)),
            tuned_from: Some("seed".into()),
            ..SceneRow::default()
        };
        let mut h = String::new();
        tuned_saving(&mut h, &tuned, "seed", &[untuned, tuned.clone()]);
        assert!(
            h.contains("50 saved per pixel (25.000%), 500 over the image"),
            "{h}"
        );
        let mut h = String::new();
        tuned_saving(&mut h, &tuned, "seed", std::slice::from_ref(&tuned));
        assert!(h.contains("no saving to show"), "{h}");
    }

    #[test]
    fn escapes_markup() {
        assert_eq!(esc("a<b>&\"c'"), "a&lt;b&gt;&amp;&quot;c&#39;");
    }

    #[test]
    fn durations_read_naturally() {
        assert_eq!(seconds(85e-9), "85 ns");
        assert_eq!(seconds(3.25e-6), "3.2 µs");
        assert_eq!(seconds(0.014), "14.0 ms");
        assert_eq!(seconds(2.5), "2.5 s");
        assert_eq!(seconds(250.0), "4m 10s");
        assert_eq!(seconds(0.0), "–");
    }

    #[test]
    fn testfloat_counts_show_both_levels_per_operation() {
        let mut r = Report::new(RunMeta::default());
        let implementations = vec!["ref-f316".to_string(), "jack".to_string()];
        for (level, cases, divergences) in [(1, 46_656, 0), (2, 1_254_528, 3)] {
            r.testfloat.push(CaseCount {
                op: "add".into(),
                level,
                cases,
                implementations: implementations.clone(),
                divergences,
            });
        }
        let page = render(&r, &History::default());
        assert!(page.contains(
            "<tr><td><code>add</code></td><td class=n>46656</td><td class=\"n ok\">0</td><td class=n>1254528</td><td class=\"n bad\">3</td><td>ref-f316, jack</td></tr>"
        ), "{page}");
        let empty = render(&Report::new(RunMeta::default()), &History::default());
        assert!(empty.contains("<p>No TestFloat step in this run.</p>"));
    }

    #[test]
    fn page_has_every_section_and_escapes_labels() {
        let mut r = Report::new(RunMeta {
            git_commit: "<x>".into(),
            ..RunMeta::default()
        });
        r.image_pairs.push(ImagePair {
            a: "ref-f316".into(),
            b: "jack".into(),
            width: 4,
            height: 2,
            pixels: 8,
            differing_pixels: 1,
            overlay: "images/o.png".into(),
            divergences: vec![PixelDivergence {
                x: 3,
                y: 1,
                first_op: Some("div((0,1,2), (0,1,3)) = (0,1,1) vs (0,1,2)".into()),
                repro: "harness localize ref-f316 jack --pixel 3,1".into(),
                ..PixelDivergence::default()
            }],
            localization: "op traces of both; 1 listed pixels localized".into(),
            ..ImagePair::default()
        });
        r.image_pairs.push(ImagePair {
            a: "ref-f316".into(),
            b: "ref-f64".into(),
            differing_pixels: 1,
            divergences: vec![PixelDivergence::default()],
            localization: "not localizable: ref-f64 computes with f64".into(),
            ..ImagePair::default()
        });
        let tally = |value, diverging| OutcomeTally {
            value,
            diverging,
            ..OutcomeTally::default()
        };
        r.stability.push(StabilityRow {
            set: "ops-nightly".into(),
            category: "underflow".into(),
            vectors: 3,
            outcomes: [
                ("jack".to_string(), tally(3, Some(2))),
                ("ref-f32".to_string(), tally(3, None)),
            ]
            .into(),
            worst: Some(WorstError {
                implementation: "ref-f32".into(),
                case: "mul(a, b)".into(),
                vector: "ops-nightly #7".into(),
                repro: Some("harness diff ref-f32 ref-f64 --vectors repro/x.json".into()),
                abs: 1e-40,
                rel: 1.0,
                ..WorstError::default()
            }),
        });
        r.implementations.push(ImplStatus {
            name: "gpu-f316".into(),
            available: true,
            open_s: 2.5,
            note: None,
        });
        let page = render(&r, &History::default());
        assert!(page.contains(
            "<td><code>gpu-f316</code></td><td><span class=ok>yes</span></td><td>2.5 s</td>"
        ));
        assert!(page.contains(
            "<tr><td>ops-nightly</td><td>underflow</td><td class=n>3</td><td>V 3 · E 0 · H 0 · D 0 · <span class=bad>≠ 2</span></td><td>V 3 · E 0 · H 0 · D 0</td>"
        ));
        assert!(page.contains("on <code>mul(a, b)</code> (ops-nightly #7)"));
        assert!(page.contains("<code>harness diff ref-f32 ref-f64 --vectors repro/x.json</code>"));
        assert!(page.contains(
            "<p>First divergent operation: not localizable: ref-f64 computes with f64</p>"
        ));
        assert!(page.contains("<td>not localizable (see above)</td>"));
        for id in [
            "summary",
            "levels",
            "testfloat",
            "renders",
            "pairs",
            "cost",
            "speed",
            "stability",
            "bench",
            "trend",
        ] {
            assert!(
                page.contains(&format!("<section id={id}>")),
                "section {id} missing"
            );
        }
        assert!(page.contains("&lt;x&gt;") && !page.contains("<x>"));
        assert!(page.contains("<title>pixel (3, 1): black vs black\ndiv((0,1,2)"));
        assert!(
            page.contains("href=\"#ref-f316-vs-jack-3-1\"")
                && page.contains("<tr id=\"ref-f316-vs-jack-3-1\">")
        );
    }
}
