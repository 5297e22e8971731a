// SPDX-License-Identifier: MIT
// Types of pixi.mjs: the PixiJS v7 renderer for posemorph.
import type { Container, Texture } from 'pixi.js';
import type { Crowd, Rig } from './posemorph.mjs';

/** Textures by list and page: drawings[list][page] (List.pages; a part's drawing in a pose is Part.regions[pose].page). */
export type Drawings = Texture[][];

/**
 * Every list's texture pages (premultiplied, no mipmaps, each list's filter): an atlas's pages from `pagesUrl`
 * (the rig file's folder; by default `baseUrl`), a rig without an atlas's drawings from `baseUrl`.
 */
export declare function loadDrawings(rig: Rig, baseUrl: string, pagesUrl?: string): Promise<Drawings>;

/** One character: one mesh per draw step, cross-fading up to eight drawings. */
export declare class CharacterView extends Container {
  constructor(rig: Rig, drawings: Drawings);
  /** Character k of the crowd's last frame (after Crowd.evaluate). */
  update(crowd: Crowd, k: number): void;
  /** Draw calls this character made in its last update (one per step). */
  readonly drawCalls: number;
}
