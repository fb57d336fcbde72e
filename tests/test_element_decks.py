"""Element cards as CalculiX writes them: an 8-node element over two lines
(the first ending with a comma), and the same model on one line."""
from helpers import run_deck

DECK = """*NODE, NSET=ALL
1, 0., 0.
2, 2., 0.
3, 2., 1.
4, 0., 1.
5, 1., 0.
6, 2., 0.5
7, 1., 1.
8, 0., 0.5
*ELEMENT, TYPE=CPS8, ELSET=E
{element}*MATERIAL, NAME=M
*ELASTIC
1000., 0.25
*SOLID SECTION, ELSET=E, MATERIAL=M
*NSET, NSET=BOT
1, 5, 2
*BOUNDARY
BOT, 2, 2
1, 1, 1
*STEP
*STATIC
*DLOAD
1, P3, 10.
*NODE PRINT
U
*END STEP
"""


def test_element_continued_on_the_next_line():
    one = run_deck("element_one_line", DECK.format(element="1, 1, 2, 3, 4, 5, 6, 7, 8\n")).ok()
    two = run_deck("element_two_lines", DECK.format(element="1, 1, 2, 3, 4, 5, 6, 7,\n8\n")).ok()
    u1 = one.listing.increments[-1].block("NODE U")
    u2 = two.listing.increments[-1].block("NODE U")
    assert list(u1["U2"]) == list(u2["U2"]) and min(u1["U2"]) < -0.009, (u1["U2"], u2["U2"])


def test_element_line_short_without_a_comma_is_an_error():
    run = run_deck("element_short", DECK.format(element="1, 1, 2, 3, 4, 5, 6, 7\n8\n"))
    assert run.rc != 0 and "element CPS8 needs an id and 8 nodes" in run.stderr, run.stderr
