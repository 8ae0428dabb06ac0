#!/usr/bin/env python3
"""MuJoCo's offscreen renderer (OSMesa) on its humanoid: the peer of render_bench.py.

usage: render_mujoco.py WIDTH HEIGHT FRAMES full|lite

The humanoid below is written after MuJoCo's documented model/humanoid/humanoid.xml
(same bodies, capsules and spheres, floor with a reflective checker material, gradient
skybox, a spot light and a head light); the pip wheel ships no model files. "full" is
MuJoCo as shipped: 4x multisampling, shadows, floor reflection, skybox. "lite" turns all
four off. Each frame is mjv_updateScene + mjr_render + readback (mujoco.Renderer.render),
median over FRAMES after 20 of warm-up. MUJOCO_GL must be osmesa (render_bench.py sets it).
"""
import statistics
import sys
import time

import mujoco

HUMANOID = """
<mujoco model="humanoid">
  <visual>
    <global offwidth="{w}" offheight="{h}" elevation="-20" azimuth="120"/>
    <quality offsamples="{samples}"/>
    <rgba haze="0.15 0.25 0.35 1"/>
  </visual>
  <asset>
    <texture type="skybox" builtin="gradient" rgb1=".3 .5 .7" rgb2="0 0 0" width="32" height="512"/>
    <texture name="body" type="cube" builtin="flat" mark="cross" width="128" height="128"
             rgb1="0.8 0.6 0.4" rgb2="0.8 0.6 0.4" markrgb="1 1 1" random="0.01"/>
    <material name="body" texture="body" texuniform="true" rgba="0.8 0.6 .4 1"/>
    <texture name="grid" type="2d" builtin="checker" width="512" height="512" rgb1=".1 .2 .3" rgb2=".2 .3 .4"/>
    <material name="grid" texture="grid" texrepeat="1 1" texuniform="true" reflectance=".2"/>
  </asset>
  <default>
    <geom type="capsule" material="body"/>
  </default>
  <worldbody>
    <geom name="floor" size="0 0 .05" type="plane" material="grid"/>
    <light name="spotlight" mode="targetbodycom" target="torso" diffuse=".8 .8 .8"
           specular="0.3 0.3 0.3" pos="0 -6 4" cutoff="30"/>
    <body name="torso" pos="0 0 1.282">
      <light name="top" pos="0 0 2" mode="trackcom"/>
      <freejoint/>
      <geom fromto="0 -.07 0 0 .07 0" size=".07"/>
      <geom fromto="-.01 -.06 -.12 -.01 .06 -.12" size=".06"/>
      <body name="head" pos="0 0 .19"><geom type="sphere" size=".09"/></body>
      <body name="waist_lower" pos="-.01 0 -.26">
        <geom fromto="0 -.06 0 0 .06 0" size=".06"/>
        <joint type="hinge" axis="0 1 0"/>
        <body name="pelvis" pos="0 0 -.165">
          <joint type="hinge" axis="1 0 0"/>
          <geom fromto="-.02 -.07 0 -.02 .07 0" size=".09"/>
          <body name="thigh_right" pos="0 -.1 -.04">
            <joint type="hinge" axis="0 1 0"/>
            <geom fromto="0 0 0 0 .01 -.34" size=".06"/>
            <body name="shin_right" pos="0 .01 -.4">
              <joint type="hinge" axis="0 -1 0"/>
              <geom fromto="0 0 0 0 0 -.3" size=".049"/>
              <body name="foot_right" pos="0 0 -.39">
                <geom fromto="-.07 -.01 0 .14 -.03 0" size=".027"/>
                <geom fromto="-.07 .01 0 .14 .03 0" size=".027"/>
              </body>
            </body>
          </body>
          <body name="thigh_left" pos="0 .1 -.04">
            <joint type="hinge" axis="0 1 0"/>
            <geom fromto="0 0 0 0 -.01 -.34" size=".06"/>
            <body name="shin_left" pos="0 -.01 -.4">
              <joint type="hinge" axis="0 -1 0"/>
              <geom fromto="0 0 0 0 0 -.3" size=".049"/>
              <body name="foot_left" pos="0 0 -.39">
                <geom fromto="-.07 -.01 0 .14 -.03 0" size=".027"/>
                <geom fromto="-.07 .01 0 .14 .03 0" size=".027"/>
              </body>
            </body>
          </body>
        </body>
      </body>
      <body name="upper_arm_right" pos="0 -.17 .06">
        <joint type="hinge" axis="2 1 1"/>
        <geom fromto="0 0 0 .16 -.16 -.16" size=".04"/>
        <body name="lower_arm_right" pos=".18 -.18 -.18">
          <joint type="hinge" axis="0 -1 1"/>
          <geom fromto=".01 .01 .01 .17 .17 .17" size=".031"/>
          <body name="hand_right" pos=".18 .18 .18"><geom type="sphere" size=".04"/></body>
        </body>
      </body>
      <body name="upper_arm_left" pos="0 .17 .06">
        <joint type="hinge" axis="-2 1 -1"/>
        <geom fromto="0 0 0 .16 .16 -.16" size=".04"/>
        <body name="lower_arm_left" pos=".18 .18 -.18">
          <joint type="hinge" axis="0 -1 -1"/>
          <geom fromto=".01 -.01 .01 .17 -.17 .17" size=".031"/>
          <body name="hand_left" pos=".18 -.18 .18"><geom type="sphere" size=".04"/></body>
        </body>
      </body>
    </body>
  </worldbody>
</mujoco>
"""


def main():
    w, h, frames, mode = int(sys.argv[1]), int(sys.argv[2]), int(sys.argv[3]), sys.argv[4]
    lite = mode == "lite"
    model = mujoco.MjModel.from_xml_string(HUMANOID.format(w=w, h=h, samples=0 if lite else 4))
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    cam = mujoco.MjvCamera()
    mujoco.mjv_defaultFreeCamera(model, cam)
    cam.lookat[:] = (0, 0, 0.9)
    cam.distance = 3.2
    with mujoco.Renderer(model, height=h, width=w) as r:
        if lite:
            for flag in (mujoco.mjtRndFlag.mjRND_SHADOW, mujoco.mjtRndFlag.mjRND_REFLECTION,
                         mujoco.mjtRndFlag.mjRND_SKYBOX):
                r.scene.flags[flag] = 0
        times = []
        for i in range(20 + frames):
            t0 = time.perf_counter()
            r.update_scene(data, camera=cam)
            if lite:
                for flag in (mujoco.mjtRndFlag.mjRND_SHADOW, mujoco.mjtRndFlag.mjRND_REFLECTION,
                             mujoco.mjtRndFlag.mjRND_SKYBOX):
                    r.scene.flags[flag] = 0
            r.render()
            if i >= 20:
                times.append(time.perf_counter() - t0)
    name = "mujoco_lite" if lite else "mujoco"
    print(f"BENCH render.{w}x{h}.{name} fps={1 / statistics.median(times):.1f}")


if __name__ == "__main__":
    main()
