// xshade watch: a report page that updates itself. The server (harness/live/live_server.cpp) adds
// this script to every page it serves, with data-event, the number of the last event announced
// when the page was served. Each later event (server-sent, on /events) is a new state of the
// report: {"event": N, "round": R, "pages": [pages that changed], "console": "what the console said"}.
//
// The index is loaded again (it keeps its filter in its address). A scene page that changed is put
// in place without a reload: the new page is fetched, its body replaces this one's, its pixel
// scripts are loaded again, and the viewer is rebuilt keeping each group's zoom, pan, mode, mask
// and pinned pixel (viewer.js's rebuild). A page with no images (a shader that does not compile
// shows its messages, with their source lines and carets) keeps the view state it had last, for
// when the images come back.
//
// Test hooks: window.xshadeLive.{event, updates} and the body's data-xshade-live attribute
// ("connected", "updating", "updated", "lost").
(function () {
  "use strict";
  const me = document.currentScript;
  const page = decodeURIComponent(location.pathname.split("/").pop() || "index.html");
  const live = {event: Number(me && me.dataset.event) || 0, updates: 0};
  window.xshadeLive = live;
  let kept = null;  // the viewer's view states, kept through pages without images
  let queue = Promise.resolve();

  const mark = (state) => { document.body.dataset.xshadeLive = state; };

  function loadScript(src) {
    return new Promise((resolve) => {
      const script = document.createElement("script");
      script.src = src;
      script.onload = script.onerror = () => { script.remove(); resolve(); };
      document.head.append(script);
    });
  }

  async function updatePage(event) {
    const viewer = window.xshadeViewer;
    if (viewer && viewer.groups.length) kept = viewer.viewStates();
    const response = await fetch(location.pathname, {cache: "no-store"});
    if (!response.ok) return;  // gone from the report: the index says why
    const fresh = new DOMParser().parseFromString(await response.text(), "text/html");
    document.title = fresh.title;
    // The new page's scripts are not run as they move in: the viewer is already loaded, and its
    // data is read from the JSON element; the pixel scripts are loaded again, at this version.
    const pixelScripts = [];
    let viewerScript = null;
    for (const script of fresh.body.querySelectorAll("script")) {
      if (script.id === "xshade-viewer-data") continue;
      const src = script.getAttribute("src");
      if (src && src.startsWith("pixels/")) pixelScripts.push(src);
      else if (src && src.endsWith("viewer.js")) viewerScript = src;
      script.remove();
    }
    const liveScript = me;
    document.body.replaceChildren(...fresh.body.childNodes);
    if (liveScript) document.body.append(liveScript);
    await Promise.all(pixelScripts.map((src) => loadScript(`${src}?v=${event.event}`)));
    if (viewer) {
      await viewer.rebuild(event.event, kept || undefined);
    } else if (viewerScript) {
      // The page had no images when it was opened (a shader that did not compile): the viewer
      // is loaded now, and builds itself from the page as it is.
      await loadScript(viewerScript);
      if (window.xshadeViewer) await window.xshadeViewer.ready;
    }
  }

  async function handle(event) {
    if (!(event.event > live.event)) return;  // this page was served after it
    live.event = event.event;
    if (!(event.pages || []).includes(page)) return;
    if (page === "index.html") { location.reload(); return; }
    mark("updating");
    try {
      await updatePage(event);
    } catch (err) {
      console.warn("xshade watch: the page could not be updated:", err);
    }
    live.updates += 1;
    mark("updated");
  }

  const events = new EventSource("/events");
  events.onopen = () => { if (!document.body.dataset.xshadeLive) mark("connected"); };
  events.onerror = () => mark("lost");  // the EventSource tries again by itself
  events.onmessage = (message) => {
    let event;
    try { event = JSON.parse(message.data); } catch (err) { return; }
    if (event.console) console.log(event.console);
    queue = queue.then(() => handle(event));
  };
})();
