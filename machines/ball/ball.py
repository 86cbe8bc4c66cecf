# A program expert (the guide): answers `ballNear` from the whiteboard input `ballDistance`.
import json, sys
distance = None
for line in sys.stdin:
    message = json.loads(line)
    if message["type"] == "input" and message["name"] == "ballDistance":
        distance = message["value"]
    elif message["type"] == "query":
        near = isinstance(distance, (int, float)) and distance < 30
        print(json.dumps({"label": message["label"], "value": near}), flush=True)
