// Interactive face map: one SVG panel per support over the head outline, points coloured by
// one field, hover for every field, a button per group (ball speed).  The data (a "maps" entry
// of the page's JSON) come from racketdyn.report.plots.map_spec.  racketdyn.drawMap(spec).
(function () {
  "use strict";
  var rd = window.racketdyn = window.racketdyn || {};
  var kit = rd.kit, colour = kit.colour, num = kit.num, esc = kit.esc, showTip = kit.showTip;
  var hideTip = kit.hideTip, buttons = kit.buttons;

  rd.drawMap = function (spec) {
    var box = document.getElementById(spec.id), holder = box.querySelector(".panels");
    var fr = spec.frame, W = fr[1] - fr[0], H = fr[3] - fr[2], f = spec.font;
    var current = spec.initial;
    function X(x) { return (x - fr[0]).toFixed(1); }
    function Y(y) { return (fr[3] - y).toFixed(1); }
    function panel(g, p, pi) {
      var lo = g.range[0], span = (g.range[1] - g.range[0]) || 1, c = spec.colour, best = -1;
      var s = '<svg class="face" viewBox="0 0 ' + W + " " + H + '" role="img">';
      s += '<text x="' + f * 0.4 + '" y="' + f * 1.2 + '" font-size="' + f +
        '" font-weight="600">' + esc(p.label) + "</text>";
      if (spec.head) {
        var h = spec.head;
        s += '<ellipse cx="' + X(h[0]) + '" cy="' + Y(h[1]) + '" rx="' + h[2] + '" ry="' + h[3] +
          '" fill="#f3f5f7" stroke="#555" stroke-width="' + f * 0.12 + '"/>';
      }
      spec.marks.forEach(function (m, k) {
        var top = spec.head ? spec.head[1] + spec.head[3] : fr[3];
        var bottom = spec.head ? spec.head[1] - spec.head[3] : fr[2];
        s += '<line x1="' + X(m.x) + '" x2="' + X(m.x) + '" y1="' + Y(top) + '" y2="' + Y(bottom) +
          '" stroke="#444" stroke-dasharray="' + f * 0.3 + " " + f * 0.2 + '" stroke-width="' +
          f * 0.08 + '"/><text x="' + X(m.x) + '" y="' +
          (Number(Y(top)) - f * (0.3 + 0.9 * k)) + '" font-size="' + f * 0.7 +
          '" text-anchor="middle" fill="#444">' + esc(m.label) + "</text>";
      });
      p.rows.forEach(function (r, i) {
        // a flagged row (its status, after the fields) is never coloured as a value
        var v = r[spec.fields.length] ? null : r[c];
        if (spec.best && v !== null && (best < 0 || v > p.rows[best][c])) { best = i; }
        s += '<circle class="pt' + (v === null ? " bad" : "") + '" data-p="' + pi +
          '" data-i="' + i + '" cx="' + X(r[0]) + '" cy="' + Y(r[1]) + '" r="' + spec.radius +
          '" fill="' + (v === null ? "#fff" : colour((v - lo) / span)) + '"/>';
      });
      if (best >= 0) {
        s += '<circle cx="' + X(p.rows[best][0]) + '" cy="' + Y(p.rows[best][1]) + '" r="' +
          spec.radius * 1.7 + '" fill="none" stroke="#d62728" stroke-width="' + f * 0.15 +
          '" pointer-events="none"/>';
      }
      return s + "</svg>";
    }
    function bar(g) {
      var field = spec.fields[spec.colour], stops = "", id = spec.id + "-grad";
      for (var k = 0; k <= 10; k++) {
        stops += '<stop offset="' + k * 10 + '%" stop-color="' + colour(k / 10) + '"/>';
      }
      var unit = field[1] ? " (" + field[1] + ")" : "";
      return '<svg class="bar" viewBox="0 0 520 44"><defs><linearGradient id="' + id + '">' +
        stops + '</linearGradient></defs><rect x="60" y="4" width="400" height="14" fill="url(#' +
        id + ')" stroke="#999" stroke-width=".5"/><text x="55" y="16" font-size="12" ' +
        'text-anchor="end">' + num(g.range[0], field[2]) + '</text><text x="465" y="16" ' +
        'font-size="12">' + num(g.range[1], field[2]) + '</text><text x="260" y="36" ' +
        'font-size="12" text-anchor="middle">' + esc(field[0] + unit + ", " + g.label) +
        "</text></svg>";
    }
    function render() {
      var g = spec.groups[current];
      holder.innerHTML = '<div class="maps">' + g.panels.map(function (p, pi) {
        return panel(g, p, pi);
      }).join("") + "</div>" + bar(g);
      box.dataset.drawn = String(holder.querySelectorAll("circle.pt").length);
      box.dataset.group = g.label;
    }
    if (spec.groups.length > 1) {
      buttons(box.querySelector(".controls"), spec.groups.map(function (g) { return g.label; }),
        current, function (i) { current = i; render(); });
    }
    holder.addEventListener("mousemove", function (ev) {
      var t = ev.target;
      if (!t.classList || !t.classList.contains("pt")) { hideTip(); return; }
      var p = spec.groups[current].panels[Number(t.dataset.p)], r = p.rows[Number(t.dataset.i)];
      var out = "<b>" + esc(p.label) + ", " + esc(spec.groups[current].label) + "</b>";
      spec.fields.forEach(function (fd, k) {
        out += "<br>" + esc(fd[0]) + ": " + num(r[k], fd[2]) + (fd[1] ? " " + esc(fd[1]) : "");
      });
      if (r[spec.fields.length]) {
        out += '<br><span class="warn">' + esc(r[spec.fields.length]) + "</span>";
      }
      showTip(ev, out);
    });
    holder.addEventListener("mouseleave", hideTip);
    render();
  };
})();
