#!/usr/bin/env python3
"""Replays a hand-made room layout as a person's review of a survey, through
`asbuilt review`'s HTTP API, and saves it: the survey's plan becomes the
annotated one and OUT/review/training/ a labelled real example (docs/review.md).

    scripts/review-from-truth.py OUT TRUTH.json [--asbuilt build/asbuilt]

OUT is a folder written by `asbuilt survey`. TRUTH.json is either
  - a plan.json made by a person on the same photo, in the same frame (the CC0
    rooms' truth.json in ../shared/data/cc0-panoramas/annotated/): the outline
    goes in with set_corners, then the ceiling height and each door and window
    in metres; or
  - a person's clicks on OUT/review/panorama.jpg (data/real-rooms/*.json):
    "corners" [{u, v}] in room order (trace), "ceiling" {u, v} or null, and
    "openings" [{kind, u0, u1, v_top, v_bottom}], as the page's own edits.
Exits non-zero, naming the step, when an edit is refused.
"""
import argparse
import json
import subprocess
import sys
import urllib.parse
import urllib.request


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("out", help="a folder written by asbuilt survey")
    ap.add_argument("truth", help="the person's plan.json of the same room, or their clicks on its photo")
    ap.add_argument("--asbuilt", default="build/asbuilt", help="the asbuilt executable")
    args = ap.parse_args()
    truth = json.load(open(args.truth))
    clicks = "corners" in truth
    if not clicks and not truth.get("rooms"):
        sys.exit(f"{args.truth}: has neither rooms[0].polygon nor corners to set")

    server = subprocess.Popen([args.asbuilt, "review", args.out, "--no-open"], stdout=subprocess.PIPE, text=True)
    try:
        first = server.stdout.readline().strip()
        if not first.startswith("asbuilt review: "):
            sys.exit(f"asbuilt review {args.out}: did not start ({first!r})")
        url = urllib.parse.urlparse(first.split(": ", 1)[1])
        token = urllib.parse.parse_qs(url.query)["token"][0]
        base = f"{url.scheme}://{url.netloc}"

        def post(path, body):
            req = urllib.request.Request(f"{base}{path}?token={token}", data=json.dumps(body).encode(),
                                         headers={"Content-Type": "application/json"}, method="POST")
            try:
                with urllib.request.urlopen(req, timeout=120) as r:
                    return json.load(r)
            except urllib.error.HTTPError as e:
                sys.exit(f"{args.out}: {body.get('op', path)} refused: {e.read().decode(errors='replace')}")

        if clicks:
            replay_clicks(post, truth)
        else:
            replay_plan(post, truth)
        state = post("/api/save", {})
        print(f"{args.out}: saved {len(state.get('files', []))} files, the training example in review/training/")
    finally:
        server.terminate()
        server.wait(timeout=10)


def replay_clicks(post, clicks):
    post("/api/edit", {"op": "trace", "points": [{"u": c["u"], "v": c["v"]} for c in clicks["corners"]]})
    if clicks.get("ceiling"):
        post("/api/edit", {"op": "ceiling", "u": clicks["ceiling"]["u"], "v": clicks["ceiling"]["v"]})
    for o in clicks.get("openings", []):
        post("/api/edit", {"op": "add_opening", **{k: o[k] for k in ("kind", "u0", "u1", "v_top", "v_bottom")}})


def replay_plan(post, truth):
    post("/api/edit", {"op": "set_corners", "corners_m": truth["rooms"][0]["polygon"]})
    height = truth.get("ceiling_height_m")
    if height:
        post("/api/edit", {"op": "ceiling", "height_m": height})
    for o in truth.get("openings", []):
        if "start" not in o:
            continue
        sill = o.get("sill") or 0.0
        post("/api/edit", {"op": "add_opening", "kind": o["kind"], "start_m": o["start"], "end_m": o["end"],
                           "bottom_m": sill, "top_m": sill + (o.get("height") or (2.0 if o["kind"] == "door" else 1.2))})

if __name__ == "__main__":
    main()
