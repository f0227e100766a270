"""The chapter "The button experiment" (book/button_experiment.ipynb): its sentences
with a word of strength beside a glued number (`STRONG_WORDS`), each a rule of the
console or of the learner that a test of the code checks."""

_ENVS = "tests/test_envs.py::"
_LEARNERS = "tests/test_learners.py::"

STRONG_WORDS = {
    "The red column never changes": (
        _LEARNERS + "test_action_weight_decides_whether_red_generalises_across_layouts",
        "rule"),
    "from the most similar press it remembers": (
        _LEARNERS + "test_ties_go_to_the_most_recent_experience", "rule"),
    "mostly the most interesting button": (
        _LEARNERS + "test_greedy_agent_presses_the_button_whose_predicted_task_is_most_"
                    "interesting", "rule"),
    "under lights it has never seen": (
        _LEARNERS + "test_action_weight_decides_whether_red_generalises_across_layouts",
        "rule"),
    "**Boxes shut before every press.**": (
        _ENVS + "test_a_press_opens_the_box_of_its_colour_and_unlit_buttons_open_nothing",
        "rule"),
    "of equally near presses it takes the most recent": (
        _LEARNERS + "test_ties_go_to_the_most_recent_experience", "rule"),
    "the red one is always button": (
        _ENVS + "test_red_never_moves_and_green_is_never_on_red", "rule"),
    "with the boxes shut before every press there are": (
        _LEARNERS + "test_agent_turns_predictions_into_tasks_and_scores_errors", "rule"),
    "in every trial two of the five buttons are lit": (
        _ENVS + "test_red_never_moves_and_green_is_never_on_red", "rule"),
    "green for every button but red": (
        _LEARNERS + "test_action_weight_decides_whether_red_generalises_across_layouts",
        "rule"),
}
"""{a fragment of the sentence: (the test that checks the rule, "rule")}, read by
book/_ext/claim_words.py."""
