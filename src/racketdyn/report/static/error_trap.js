// Any script error is recorded on <html data-errors=...>, where the browser tests look.
window.onerror = function (message) {
  var root = document.documentElement;
  root.setAttribute("data-errors", (root.getAttribute("data-errors") || "") + message + "; ");
};
