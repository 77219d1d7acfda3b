// Shared pieces of the report's plots: the viridis colour scale, number formatting, HTML
// escaping, the hover tooltip (#tip) and button rows.  Exposed as window.racketdyn.kit.
(function () {
  "use strict";
  var rd = window.racketdyn = window.racketdyn || {};
  function tipElement() { return document.getElementById("tip"); }
  var VIR = [[68, 1, 84], [72, 40, 120], [62, 73, 137], [49, 104, 142], [38, 130, 142],
    [31, 158, 137], [53, 183, 121], [110, 206, 88], [181, 222, 43], [253, 231, 37]];
  function colour(t) {
    t = Math.max(0, Math.min(1, t)) * (VIR.length - 1);
    var i = Math.min(Math.floor(t), VIR.length - 2), u = t - i, a = VIR[i], b = VIR[i + 1];
    return "rgb(" + [0, 1, 2].map(function (k) {
      return Math.round(a[k] + u * (b[k] - a[k]));
    }).join(",") + ")";
  }
  function num(v, d) {
    return v === null || v === undefined ? "–" : (typeof v === "number" ? v.toFixed(d) : v);
  }
  function esc(s) {
    return String(s).replace(/[&<>"]/g, function (c) {
      return { "&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;" }[c];
    });
  }
  function sci(v) { return v === null ? "–" : v.toExponential(3); }
  function showTip(ev, content) {
    var tip = tipElement();
    tip.innerHTML = content;
    tip.hidden = false;
    var x = ev.clientX + 14, y = ev.clientY + 14;
    if (x + tip.offsetWidth > window.innerWidth) { x = ev.clientX - tip.offsetWidth - 14; }
    if (y + tip.offsetHeight > window.innerHeight) { y = ev.clientY - tip.offsetHeight - 14; }
    tip.style.left = x + "px";
    tip.style.top = y + "px";
  }
  function hideTip() { tipElement().hidden = true; }
  function buttons(holder, labels, active, onPick) {
    holder.insertAdjacentHTML("beforeend", labels.map(function (l, i) {
      return '<button type="button" data-pick="' + i + '"' + (i === active ? ' class="on"' : "") +
        ">" + esc(l) + "</button>";
    }).join(""));
    holder.addEventListener("click", function (ev) {
      var b = ev.target.closest("button[data-pick]");
      if (!b) { return; }
      holder.querySelectorAll("button[data-pick]").forEach(function (x) {
        x.classList.toggle("on", x === b);
      });
      onPick(Number(b.dataset.pick));
    });
  }
  function niceStep(span, n) {
    var step = Math.pow(10, Math.floor(Math.log10(span / n))), m = span / n / step;
    return step * (m < 2 ? 1 : m < 5 ? 2 : 5);
  }
  rd.kit = { colour: colour, num: num, esc: esc, sci: sci, showTip: showTip, hideTip: hideTip,
    buttons: buttons, niceStep: niceStep };
})();
