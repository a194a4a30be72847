// The style sheet of the HTML page of `dqskin report` (internal to lib/report), inline in the page so that
// it needs nothing else. lbs, dqs and dib have one colour each, everywhere (table legend, charts); the
// palette is Okabe and Ito's, which colour-blind readers can tell apart, and dib, the reference, is a
// dashed dark line.
#pragma once

namespace dqskin::report_detail {

inline constexpr const char* kReportStyle = R"css(
:root { --lbs: #d55e00; --dqs: #0072b2; --dib: #2b2b2b; --twist: #7b3294; --bend: #009e73;
  --ink: #1d2329; --muted: #5f6b76; --line: #dde2e7; --paper: #ffffff; --back: #f5f6f8; }
* { box-sizing: border-box; }
body { margin: 0; background: var(--back); color: var(--ink);
  font: 14px/1.45 system-ui, -apple-system, "Segoe UI", Roboto, "Helvetica Neue", Arial, sans-serif; }
main { max-width: 1180px; margin: 0 auto; padding: 24px 20px 48px; }
h1 { font-size: 22px; margin: 0 0 4px; font-weight: 600; }
h2 { font-size: 17px; margin: 32px 0 10px; font-weight: 600; }
h3 { font-size: 15px; margin: 0 0 6px; font-weight: 600; }
h4 { font-size: 13px; margin: 12px 0 4px; font-weight: 600; color: var(--muted); }
a { color: var(--dqs); text-decoration: none; }
a:hover { text-decoration: underline; }
.card { background: var(--paper); border: 1px solid var(--line); border-radius: 8px; padding: 14px 16px; margin: 12px 0; }
.facts { display: flex; flex-wrap: wrap; gap: 4px 22px; margin: 6px 0 0; color: var(--muted); }
.facts div { display: flex; gap: 6px; }
.facts dt { font-weight: 600; }
.facts dd { margin: 0; color: var(--ink); font-variant-numeric: tabular-nums; }
.verdict { border-left: 5px solid var(--muted); }
.verdict p { margin: 6px 0 0; }
.badge { display: inline-block; padding: 1px 8px; border-radius: 10px; font-size: 12px; font-weight: 600;
  background: #eceff2; color: var(--muted); vertical-align: 1px; margin-right: 6px; white-space: nowrap; }
.v-lbs-fine .badge, .badge.v-lbs-fine { background: #e4f3ea; color: #1e6b3a; }
.v-use-dqs .badge, .badge.v-use-dqs { background: #e1eefa; color: #0b4f8a; }
.v-dqs-closer .badge, .badge.v-dqs-closer { background: #e8eefc; color: #2f4a9a; }
.v-add-twist-joints .badge, .badge.v-add-twist-joints { background: #fff1d6; color: #8a5300; }
.v-dqs-bulges .badge, .badge.v-dqs-bulges { background: #f8e3ee; color: #8a1c4a; }
.verdict.v-lbs-fine { border-left-color: #2f9e5b; }
.verdict.v-use-dqs, .verdict.v-dqs-closer { border-left-color: var(--dqs); }
.verdict.v-add-twist-joints { border-left-color: #e69f00; }
.verdict.v-dqs-bulges { border-left-color: #cc3d7a; }
.methods { display: flex; flex-wrap: wrap; gap: 4px 20px; list-style: none; padding: 0; margin: 8px 0 0; color: var(--muted); }
.swatch { display: inline-block; width: 18px; height: 0; border-top: 3px solid; vertical-align: 4px; margin-right: 6px; }
.swatch.lbs { border-color: var(--lbs); } .swatch.dqs { border-color: var(--dqs); }
.swatch.dib { border-top-style: dashed; border-color: var(--dib); }
.swatch.twist { border-color: var(--twist); } .swatch.bend { border-color: var(--bend); }
.table-wrap { overflow-x: auto; }
table { border-collapse: collapse; width: 100%; background: var(--paper); font-size: 13px; }
th, td { padding: 5px 8px; border-bottom: 1px solid var(--line); text-align: left; vertical-align: top; }
th { font-weight: 600; color: var(--muted); background: #fafbfc; vertical-align: bottom; }
th .unit { display: block; font-weight: 400; }
td.num { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
td.none { color: #a3acb5; }
td.pct { color: var(--muted); }
td.name { white-space: nowrap; }
td.name .parent { display: block; font-size: 11px; color: var(--muted); }
tr.flagged td:first-child { box-shadow: inset 3px 0 0 #e69f00; }
td.verdict-text { min-width: 260px; }
th:not(:first-child):not(:last-child) { text-align: right; }
.clip-body { display: flex; flex-wrap: wrap; gap: 16px; align-items: flex-start; }
.meta { font-weight: 400; color: var(--muted); font-size: 13px; margin-left: 6px; }
figure { margin: 0; }
figure.sheet img { display: block; max-width: 100%; height: auto; border: 1px solid var(--line); border-radius: 4px;
  background: #111; image-rendering: auto; }
figure.sheet { flex: 1 1 420px; max-width: 720px; }
figcaption { font-size: 12px; color: var(--muted); margin-top: 6px; }
.scale { display: flex; align-items: center; gap: 6px; margin-top: 4px; }
.scale .bar { display: inline-block; width: 160px; height: 10px; border-radius: 2px;
  background: linear-gradient(to right, #272789, #00cbe7, #ffec00, #e70000); }
.note { color: var(--muted); font-style: italic; margin: 6px 0; }
.missing { color: #b3261e; }
.charts { display: grid; grid-template-columns: repeat(auto-fill, minmax(300px, 1fr)); gap: 8px 16px; }
svg.chart { width: 100%; max-width: 360px; height: auto; display: block; overflow: visible;
  font-family: system-ui, -apple-system, "Segoe UI", Roboto, "Helvetica Neue", Arial, sans-serif; }
svg.chart .title { font-size: 11.5px; font-weight: 600; fill: var(--ink); }
svg.chart .legend, svg.chart .unit { font-size: 10.5px; fill: var(--muted); }
svg.chart .tick { font-size: 10px; fill: var(--muted); font-variant-numeric: tabular-nums; }
svg.chart .grid { stroke: #eef0f3; }
svg.chart .axis { stroke: #9aa4ad; fill: none; }
svg.chart .reference { stroke: #9aa4ad; stroke-dasharray: 2 3; }
svg.chart .marker { stroke: #b3261e; stroke-dasharray: 3 3; opacity: 0.6; }
svg.chart .marker-label { font-size: 9.5px; fill: #b3261e; }
svg.chart .empty { font-size: 11px; fill: #a3acb5; }
svg .lbs, svg .dqs, svg .dib, svg .twist, svg .bend { fill: none; stroke-width: 1.5; stroke-linejoin: round; }
svg .lbs { stroke: var(--lbs); } svg .dqs { stroke: var(--dqs); }
svg .dib { stroke: var(--dib); stroke-dasharray: 4 3; } svg .twist { stroke: var(--twist); }
svg .bend { stroke: var(--bend); stroke-dasharray: 5 2; }
svg .dot { stroke: none; }
svg .dot.lbs { fill: var(--lbs); } svg .dot.dqs { fill: var(--dqs); } svg .dot.dib { fill: var(--dib); }
svg .dot.twist { fill: var(--twist); } svg .dot.bend { fill: var(--bend); }
article.joint { scroll-margin-top: 12px; }
article.joint > p { margin: 0 0 4px; }
details.fine > summary { cursor: pointer; font-weight: 600; margin: 16px 0 4px; }
details.settings > summary { cursor: pointer; color: var(--muted); margin-top: 8px; }
details.settings dl { display: grid; grid-template-columns: max-content 1fr; gap: 2px 14px; margin: 6px 0 0; font-size: 13px; }
details.settings dt { color: var(--muted); }
details.settings dd { margin: 0; font-variant-numeric: tabular-nums; }
footer { color: var(--muted); font-size: 12px; margin-top: 36px; }
)css";

}  // namespace dqskin::report_detail
