// The README.md written into every recording.
#include "robots/replay/recording.h"

namespace coopmap {

std::string recordingReadme() {
  return R"(# coopmap recording (format `coopmap-recording`, version 2)

The raw stream of one or more robots with trinocular stereo cameras: per sensing cycle the
three camera images, the time and the odometry pose at capture; at the control rate the
odometry and the motion commands; the rig calibration and the robot description; and, when
the recording comes from the coopmap simulator, the ground truth beside it. Everything is
plain text (YAML, CSV) or lossless 8-bit PNG, readable without coopmap.

`coopmap replay DIR --out OUT` runs the same robot agents on it (a recording cannot be
steered: they decide as they did live, and the commands go nowhere) and writes the same
outputs as the live run (`coopmap run WORLD --record DIR`); replaying a simulator recording
reproduces the live run's maps and traverse logs bit for bit.

## Conventions

Units are SI: metres, radians, seconds. Frames follow ROS REP-103 (x forward, y left, z up,
angles counter-clockwise). A 2D pose `x,y,theta` is the robot frame in the odometry frame
(odometry, which starts at the origin) or in the world (ground truth). Times are seconds on the robot's clock. Numbers
are written with 17 significant digits, so they read back as the exact doubles written.
CSV files have a header line, comma-separated fields, no quoting, and end in a newline.

## Layout

```
DIR/README.md          this file
DIR/dataset.yaml       format, version, source, world, seed, rates, map limits, robots
DIR/floor.png          optional (simulator): 255 where the world has a floor, else 0
DIR/<robot>/robot.yaml        the robot description and the rig calibration
DIR/<robot>/frames.csv        frame,stamp,x,y,theta,segment: one row per sensing cycle
DIR/<robot>/images/NNNNNN_reference.png   the frame's three images, NNNNNN = frame, 6 digits
DIR/<robot>/images/NNNNNN_horizontal.png
DIR/<robot>/images/NNNNNN_vertical.png
DIR/<robot>/odometry.csv      stamp,x,y,theta: the odometry pose at every control step
DIR/<robot>/commands.csv      stamp,kind,linear,angular,amount: the command of every step
DIR/<robot>/status.csv        stamp,bumped,contact_events,segment_active,bump_bearing: the
                              base's status at every step
DIR/<robot>/agent.yaml        the robot's agent: its setup (name, mode, map, home base as
                              designed, route) and settings
DIR/<robot>/groundtruth.csv   optional (simulator): stamp,x,y,theta, the true pose per step
DIR/<robot>/groundtruth_occupancy.png  optional (simulator): 255 where a solid stands
                                       between the floor and the robot's swept height
```

A recording is written into `DIR.incomplete` and renamed to `DIR` when complete, and
`dataset.yaml` is written last: a folder without `dataset.yaml` is not a complete recording.

### dataset.yaml

- `format`: `coopmap-recording`; `version`: `2` (version 1 had no `status.csv`, no
  `agent.yaml` and no `shared_map`). Readers must reject other versions.
- `source`: where the stream came from (`simulator`); `world`, `world_file`, `seed`: the
  simulated world and seed, when there was one.
- `sensing_rate`, `control_rate`: Hz.
- `map`: `{resolution, origin: [x, y], width, height}`, the occupancy grid the live run
  mapped into: cell (ix, iy) covers `origin + [ix, iy] * resolution` to
  `origin + [ix + 1, iy + 1] * resolution` (m, map frame: the home base's).
- `shared_map`: whether the robots' agents shared a map during the run (a replay gives
  them one again).
- `robots`: a list of `{name, frames, start, map_in_world}`: the folder name, the number of
  rows of `frames.csv` (fewer rows means a truncated file), and (simulator) the true start
  pose `[x, y, theta]` and where the map frame stands in the world `[x, y, theta]`.

### robot.yaml

Body and limits: `model`, `body_radius`, `body_height`, `swept_height` (m: everything up to
this height can hit the robot), `max_linear_speed` (m/s), `max_angular_speed` (rad/s),
`max_linear_accel` (m/s^2), `max_angular_accel` (rad/s^2).

`rig`: a rectified trinocular rig. All three cameras share the pinhole intrinsics `width`,
`height` (pixels), `fx`, `fy`, `cx`, `cy` (pixels; pixel centres at integer coordinates, the
OpenCV convention) and the same orientation. Camera frames follow OpenCV (x right, y down,
z forward). `horizontal_offset` and `vertical_offset` are the partner cameras' positions in
the reference camera's frame (m). `mount_position` is the reference camera's position in the
robot frame (m); it looks along the robot's +x.

### frames.csv

`frame` counts from 0 in steps of 1; `stamp` (s) increases strictly; `x,y,theta` is the
odometry pose at capture; `segment` is the motion under way since the previous frame (`stop`,
`turn` in place, `straight`), the label the traverse log keeps. The images of frame N are
`images/NNNNNN_{reference,horizontal,vertical}.png`: 8-bit single-channel PNG of the rig's
size, rectified; the horizontal partner is offset by `horizontal_offset`, the vertical by
`vertical_offset`.

### odometry.csv, groundtruth.csv, commands.csv, status.csv

One row per control step (`control_rate`), stamps strictly increasing, the same stamps in
each. `kind` is `velocity` (`linear` m/s along +x and `angular` rad/s CCW, held until the
next command), `turn` (turn in place by `amount` rad, CCW positive) or `straight` (drive
`amount` m, negative backwards), executed by the base on its encoders; unused fields are 0.
In `status.csv`, `bumped` and `segment_active` are 0 or 1, `contact_events` counts distinct
contacts since the start, and `bump_bearing` (rad, robot frame) is where the base is
touched, empty when it does not say.

### agent.yaml

What the robot's agent (`core/agent/robot_agent.h`) was set up with: `name`, `mode` (`route`,
`explore` or `driven`), the path planner's `seed`, `priority`, `map` (its grid), `home_base`
(the home base as designed, which defines the map frame), `route` (map frame) and
`settings` (docs/settings.md).

### PNG grids

`floor.png` and `groundtruth_occupancy.png` cover `map` one pixel per cell, north up: pixel
row 0 is cell row `iy = height - 1`, column `ix` is cell column `ix`.

## Reading it in Python

```python
import csv, yaml, imageio.v3 as iio
info = yaml.safe_load(open("DIR/dataset.yaml"))
assert info["format"] == "coopmap-recording" and info["version"] == 2
for robot in info["robots"]:
    name = robot["name"]
    for row in csv.DictReader(open(f"DIR/{name}/frames.csv")):
        n = int(row["frame"])
        ref = iio.imread(f"DIR/{name}/images/{n:06d}_reference.png")
```
)";
}

}  // namespace coopmap
